#!/usr/bin/python3
"""Plots the draft force of a tillage run: the force the soil exerts on a tool against its
travel, over time, with its mean over the steady window.

Usage: scripts/plot_draft.py TIMESERIES_CSV OUT_PNG [--tool NAME] [--axis x|y|z]
       [--steady START END] [--append-csv FILE --label TEXT]

The draft is minus the tool's force component along its travel axis (default: the mesh column
prefix NAME = "sweep", axis x, and a travel along +x). The steady window defaults to the second
half of the run. Prints the mean and standard deviation of the draft over the window and,
with --append-csv, appends them to FILE as the row "TEXT,mean,std" (as printed).
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("png")
    parser.add_argument("--tool", default="sweep")
    parser.add_argument("--axis", default="x", choices=["x", "y", "z"])
    parser.add_argument("--steady", nargs=2, type=float, metavar=("START", "END"))
    parser.add_argument("--append-csv", metavar="FILE")
    parser.add_argument("--label", metavar="TEXT", help="first fields of the appended row")
    args = parser.parse_args()
    if args.append_csv and args.label is None:
        parser.error("--append-csv needs --label")
    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    column = f"{args.tool}_f{args.axis}"
    if not rows or column not in rows[0]:
        sys.exit(f"plot_draft.py: {args.csv} has no column '{column}'")
    time = [float(r["time"]) for r in rows]
    draft = [-float(r[column]) for r in rows]
    start, end = args.steady if args.steady else (time[-1] / 2, time[-1])
    window = [d for t, d in zip(time, draft) if start <= t <= end]
    if not window:
        sys.exit(f"plot_draft.py: no rows in the steady window {start}..{end} s")
    mean = sum(window) / len(window)
    std = (sum((d - mean) ** 2 for d in window) / len(window)) ** 0.5
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(time, draft, lw=0.8, label="draft force")
    ax.hlines(mean, start, end, colors="C3", lw=2,
              label=f"mean {start:.2f}–{end:.2f} s: {mean:.1f} ± {std:.1f} N")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("draft force [N]")
    ax.set_title(f"{args.tool}: draft force (−F{args.axis})")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right")
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)
    print(f"draft force over {start:.3g}–{end:.3g} s: {mean:.4g} ± {std:.3g} N "
          f"({len(window)} rows); plot: {args.png}")
    if args.append_csv:
        with open(args.append_csv, "a") as table:
            table.write(f"{args.label},{mean:.4g},{std:.3g}\n")


if __name__ == "__main__":
    main()
