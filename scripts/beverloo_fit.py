#!/usr/bin/python3
"""Fits Beverloo's law to silo discharge runs and compares its constants with the literature.

Usage: scripts/beverloo_fit.py BED_H5 D1=RUN1 D2=RUN2 ... [--window T0 T1] [--png FILE]
                               [--csv FILE] [--gravity G]

BED_H5 is the settled bed the runs started from (a bed or checkpoint file); each Di=RUNi names
an orifice diameter in metres and the output folder of its discharge run (its timeseries.csv:
the columns `time` and `removed` are read). With fewer than four runs (too few for a line and
its errors) it prints their discharge rates and fits nothing.

Beverloo et al. (1961), Chem. Eng. Sci. 15:260: the mass flow rate from a flat-bottomed silo
through a round orifice of diameter D is steady (independent of the head) and

    W = C ρ_b √g (D − k d)^{5/2},

with ρ_b the bulk density, d the grain diameter and, as usually quoted for cohesionless grains,
C ≈ 0.55–0.65 and k ≈ 1.3–1.5. Hence W^{2/5} is linear in D: slope
s = (C ρ_b √g)^{2/5}, intercept −s k d, and a least-squares line through (D, W^{2/5}) gives
C = s^{5/2} / (ρ_b √g) and k = −intercept / (s d), with standard errors from the line's
covariance (first-order propagation).

From the bed: ρ_b = φ ρ_p, φ the solid fraction of the spheres whose centres lie in the silo's
core (two mean diameters from every wall, the floor and the bed's top); d the mean diameter;
m the mean grain mass. From each run: the rate of grains leaving (slope of the `removed`
column by least squares over the window, default 0.1 s to the end), times m; the rates over the
window's two halves show whether the flow was steady.

Exit status: 0 when both constants agree with the literature ranges within two standard
errors, 1 when either does not, 2 on bad input.
"""
import argparse
import csv
import math
import sys

import h5py
import numpy as np

C_RANGE = (0.55, 0.65)
K_RANGE = (1.3, 1.5)


def bed_properties(path, density):
    """Solid fraction of the core, mean diameter and mean grain mass of a bed file."""
    with h5py.File(path, "r") as f:
        xr = np.asarray(f["position_radius"])
    x, r = xr[:, :3], xr[:, 3]
    d = 2 * r.mean()
    lo = x.min(axis=0) - r.mean() + 2 * d
    hi = x.max(axis=0) + r.mean() - 2 * d
    inside = np.all((x > lo) & (x < hi), axis=1)
    solid = (4 / 3 * math.pi * r[inside] ** 3).sum()
    phi = solid / np.prod(hi - lo)
    mass = (density * 4 / 3 * math.pi * r**3).mean()
    return phi, d, mass, len(r)


def slope(t, y):
    """Least-squares slope of y over t."""
    return np.polyfit(t, y, 1)[0]


def discharge_rate(run, window, mass):
    """Mass flow rate over the window and over its two halves, from a run's time series."""
    with open(f"{run}/timeseries.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    t = np.array([float(row["time"]) for row in rows])
    removed = np.array([float(row["removed"]) for row in rows])
    t0 = window[0]
    t1 = window[1] if window[1] is not None else t[-1]
    mid = 0.5 * (t0 + t1)

    def rate(a, b):
        sel = (t >= a) & (t <= b)
        if sel.sum() < 3:
            raise KeyError(f"{run}: fewer than 3 time-series rows in {a}..{b} s")
        return mass * slope(t[sel], removed[sel])
    return rate(t0, t1), rate(t0, mid), rate(mid, t1), int(removed[-1])


def fit_beverloo(diameters, rates, rho_b, g, d):
    """C, k and their standard errors from the line W^{2/5} = s D + b."""
    (s, b), cov = np.polyfit(diameters, np.asarray(rates) ** 0.4, 1, cov=True)
    c = s**2.5 / (rho_b * math.sqrt(g))
    k = -b / (s * d)
    # gradients of C(s) and k(s, b)
    dc = np.array([2.5 * s**1.5 / (rho_b * math.sqrt(g)), 0.0])
    dk = np.array([b / (s**2 * d), -1 / (s * d)])
    return c, k, math.sqrt(dc @ cov @ dc), math.sqrt(dk @ cov @ dk), s, b


def agrees(value, error, bounds):
    return value + 2 * error >= bounds[0] and value - 2 * error <= bounds[1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bed")
    parser.add_argument("runs", nargs="+", metavar="D=RUN")
    parser.add_argument("--density", type=float, default=2500.0, help="grain density [kg/m^3]")
    parser.add_argument("--gravity", type=float, default=9.81, help="|g| [m/s^2]")
    parser.add_argument("--window", nargs=2, default=["0.1", "end"], metavar=("T0", "T1"))
    parser.add_argument("--png")
    parser.add_argument("--csv")
    args = parser.parse_args()
    try:
        runs = [(float(a), b) for a, b in (item.split("=", 1) for item in args.runs)]
        window = (float(args.window[0]), None if args.window[1] == "end" else float(args.window[1]))
    except ValueError as e:
        print(f"beverloo_fit.py: bad argument: {e}", file=sys.stderr)
        return 2
    runs.sort()
    try:
        phi, d, mass, grains = bed_properties(args.bed, args.density)
        measured = [discharge_rate(run, window, mass) for _, run in runs]
    except (OSError, KeyError) as e:
        print(f"beverloo_fit.py: cannot read a bed or time series: {e}", file=sys.stderr)
        return 2
    rho_b = phi * args.density
    print(f"bed: {grains} grains, mean diameter {d * 1e3:.3f} mm, core solid fraction {phi:.4f}, "
          f"bulk density {rho_b:.1f} kg/m^3")
    diameters = np.array([D for D, _ in runs])
    if len(runs) < 4:
        for (D, run), (w, first, second, left) in zip(runs, measured):
            print(f"{run}: D {D * 1e3:.1f} mm, W = {w:.5f} kg/s (halves {first:.5f}, "
                  f"{second:.5f}), {left} grains left")
        return 0
    rates = np.array([m[0] for m in measured])
    c, k, c_err, k_err, s, b = fit_beverloo(diameters, rates, rho_b, args.gravity, d)
    print(f"{'D [mm]':>7} {'D/d':>6} {'W [kg/s]':>10} {'1st half':>9} {'2nd half':>9} "
          f"{'fit':>9} {'fit/W-1':>8} {'left':>6}")
    rows = []
    for D, (w, first, second, left) in zip(diameters, measured):
        fitted = (s * D + b) ** 2.5 if s * D + b > 0 else 0.0
        rows.append((D, D / d, w, first, second, fitted, left))
        print(f"{D * 1e3:7.1f} {D / d:6.2f} {w:10.5f} {first:9.5f} {second:9.5f} {fitted:9.5f} "
              f"{fitted / w - 1:+8.3f} {left:6d}")
    print(f"Beverloo fit: C = {c:.3f} ± {c_err:.3f}, k = {k:.2f} ± {k_err:.2f} "
          f"(literature C {C_RANGE[0]}–{C_RANGE[1]}, k {K_RANGE[0]}–{K_RANGE[1]})")
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            out = csv.writer(f)
            out.writerow(["D", "D_over_d", "W", "W_first_half", "W_second_half", "W_fit", "left"])
            out.writerows(rows)
    if args.png:
        plot(args.png, diameters, rates, s, b, d, c, k)
    ok = agrees(c, c_err, C_RANGE) and agrees(k, k_err, K_RANGE)
    print("agrees with the literature ranges within two standard errors" if ok else
          "DISAGREES with the literature ranges beyond two standard errors")
    return 0 if ok else 1


def plot(path, diameters, rates, s, b, d, c, k):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(diameters / d, rates**0.4, "o", label="discharge runs")
    line = np.linspace(-b / s, diameters.max() * 1.05, 50)
    ax.plot(line / d, s * line + b, "-", label=f"Beverloo fit: C = {c:.3f}, k = {k:.2f}")
    ax.set_xlabel("orifice diameter D / grain diameter d")
    ax.set_ylabel("W^(2/5) [(kg/s)^(2/5)]")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
