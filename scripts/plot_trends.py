#!/usr/bin/python3
"""Plots the draft-force trends of scripts/cultivator_trends.sh: one PNG per parameter (mean
draft with its standard deviation over the steady window), with a least-squares line and its
slope printed for the parameters expected to be linear (density, restitution).

Usage: scripts/plot_trends.py TRENDS_CSV OUT_DIR
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "density": "density [kg/m³]",
    "restitution": "coefficient of restitution [-]",
    "young": "Young's modulus [Pa]",
    "friction": "friction coefficient μ_s = μ_d [-]",
}
LINEAR = {"density", "restitution"}


def fit(xs, ys):
    """Least-squares line y = a + b x."""
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    return my - b * mx, b


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    with open(sys.argv[1], newline="") as f:
        rows = list(csv.DictReader(f))
    for name, label in LABELS.items():
        points = sorted((float(r["value"]), float(r["draft_mean_N"]), float(r["draft_std_N"]))
                        for r in rows if r["parameter"] == name)
        if not points:
            continue
        xs, ys, es = zip(*points)
        fig, ax = plt.subplots(figsize=(5, 3.6))
        ax.errorbar(xs, ys, yerr=es, fmt="o-", capsize=3, label="mean ± std over 0.45–0.84 s")
        if name in LINEAR and len(xs) > 1:
            a, b = fit(xs, ys)
            ax.plot([xs[0], xs[-1]], [a + b * xs[0], a + b * xs[-1]], "--",
                    label=f"fit: {a:.1f} + {b:.4g}·x N")
            print(f"{name}: draft = {a:.4g} + {b:.4g} x N")
        if name == "young":
            ax.set_xscale("log")
        ax.set_xlabel(label)
        ax.set_ylabel("draft force [N]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        path = f"{sys.argv[2]}/trend_{name}.png"
        fig.savefig(path, dpi=120)
        print(f"{name}: {', '.join(f'{x:g}: {y:.1f} N' for x, y in zip(xs, ys))}; plot: {path}")


if __name__ == "__main__":
    main()
