#!/usr/bin/python3
"""Fits Janssen's saturation law to the floor loads of sliding-wall columns.

Each run is BED=DIR: the column's bed file (HDF5, for its mass and packing) and the folder of
the slide's timeseries.csv, whose columns floor_fz and, for each side wall x0, x1, y0, y1, its
normal force (x0_fx, x1_fx, y0_fy, y1_fy) and friction (<wall>_fz) are the forces the grains
exert [N] (inputs/silo/janssen_slide.toml). Over the last WINDOW seconds of each run, in BLOCKS
blocks, it averages the apparent mass M_app = -floor_fz / g (with the standard error of the
block means), the walls' friction S and normal force N; then fits
    M_app = M_sat (1 - exp(-M / M_sat))
by least squares and prints M_sat with its standard error, the largest residual, the
saturation length lambda = M_sat / (rho_b A) and the lateral stress ratio
K = L / (4 mu_mob lambda), with mu_mob = S / N and rho_b of the tallest column.

Usage: scripts/janssen_fit.py [--side L] [--window S] [--blocks N] BED=DIR [BED=DIR ...]
Exit 2 on bad input.
"""
import argparse
import csv
import math
import sys

import h5py
import numpy as np

G = 9.81
SIDE_WALLS = (("x0", "x"), ("x1", "x"), ("y0", "y"), ("y1", "y"))


def fail(message):
    print(f"janssen_fit.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_bed(path, side):
    """Mass [kg], solid density [kg/m^3] and the solid fraction of the whole section between
    4 d above the floor and 4 d below the 99th percentile of the centre heights."""
    try:
        with h5py.File(path, "r") as f:
            xr = np.asarray(f["position_radius"])
            inv_mass = np.asarray(f["velocity_inv_mass"])[:, 3]
    except (OSError, KeyError) as e:
        fail(f"{path}: not a bed file ({e})")
    mass = 1 / inv_mass
    z, r = xr[:, 2], xr[:, 3]
    density = float(np.sum(mass) / np.sum(4 / 3 * math.pi * r**3))
    d = 2 * float(np.mean(r))
    lo, hi = 4 * d, float(np.percentile(z, 99)) - 4 * d

    def below(plane):  # volume of each sphere below the plane
        h = np.clip(plane - (z - r), 0, 2 * r)
        return math.pi * h * h * (3 * r - h) / 3

    fraction = float(np.sum(below(hi) - below(lo)) / (side * side * (hi - lo))) if hi > lo else 0
    return float(np.sum(mass)), density, fraction


def read_loads(folder, window, blocks):
    """Block means of M_app, S and N and the net horizontal force over the last `window` s."""
    path = f"{folder}/timeseries.csv"
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    needed = ["time", "floor_fz"] + [f"{w}_f{a}" for w, a in SIDE_WALLS] + \
        [f"{w}_fz" for w, _ in SIDE_WALLS]
    if not rows or any(k not in rows[0] for k in needed):
        fail(f"{path}: needs the columns {', '.join(needed)}")
    data = {k: np.array([float(row[k]) for row in rows]) for k in needed}
    t = data["time"]
    chosen = t > t[-1] - window
    if np.count_nonzero(chosen) < 2 * blocks:
        fail(f"{path}: fewer than {2 * blocks} rows in the last {window} s")
    apparent = -data["floor_fz"][chosen] / G
    shear = -sum(data[f"{w}_fz"][chosen] for w, _ in SIDE_WALLS)
    normal = sum(np.abs(data[f"{w}_f{a}"][chosen]) for w, a in SIDE_WALLS)
    net_x = data["x0_fx"][chosen] + data["x1_fx"][chosen]
    means = np.array([np.mean(b) for b in np.array_split(apparent, blocks)])
    return {
        "apparent": float(np.mean(means)),
        "error": float(np.std(means, ddof=1) / math.sqrt(blocks)),
        "shear": float(np.mean(shear)),
        "normal": float(np.mean(normal)),
        "net_x": float(np.mean(net_x)),
    }


def fit_saturation(mass, apparent):
    """Least-squares M_sat of M_sat (1 - exp(-M / M_sat)), its standard error, residuals."""
    def model(s):
        return s * (1 - np.exp(-mass / s))

    def error(log_s):
        return float(np.sum((apparent - model(math.exp(log_s)))**2))

    a, b = math.log(1e-3 * mass.max()), math.log(1e3 * mass.max())
    ratio = (math.sqrt(5) - 1) / 2
    while b - a > 1e-10:  # golden-section search on log M_sat
        c, d = b - ratio * (b - a), a + ratio * (b - a)
        if error(c) < error(d):
            b = d
        else:
            a = c
    s = math.exp((a + b) / 2)
    residual = apparent - model(s)
    x = mass / s
    slope = (1 - np.exp(-x)) - x * np.exp(-x)  # d model / d M_sat
    dof = max(len(mass) - 1, 1)
    se = math.sqrt(float(np.sum(residual**2)) / dof / float(np.sum(slope**2)))
    return s, se, residual


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", metavar="BED=DIR")
    parser.add_argument("--side", type=float, default=0.04, help="column side L [m]")
    parser.add_argument("--window", type=float, default=0.15, help="averaging window [s]")
    parser.add_argument("--blocks", type=int, default=6, help="blocks for the standard error")
    args = parser.parse_args()
    if args.blocks < 2 or args.window <= 0 or args.side <= 0:
        fail("--blocks must be at least 2, --window and --side positive")
    columns = []
    for run in args.runs:
        bed, sep, folder = run.partition("=")
        if not sep or not bed or not folder:
            fail(f"'{run}': expected BED=DIR")
        mass, density, fraction = read_bed(bed, args.side)
        columns.append((mass, density, fraction, read_loads(folder, args.window, args.blocks)))
    columns.sort(key=lambda c: c[0])
    print("    M [kg]  M_app [kg]  +- SE      M_app/M  mu_mob  (floor+S)/Mg-1  net F_x/Mg")
    for mass, _, _, c in columns:
        balance = (c["apparent"] * G + c["shear"]) / (mass * G) - 1
        print(f"  {mass:8.4f}  {c['apparent']:9.5f}  {c['error']:8.5f}  {c['apparent'] / mass:7.4f}"
              f"  {c['shear'] / c['normal']:6.4f}  {balance:+14.5f}  {c['net_x'] / (mass * G):+10.5f}")
    if len(columns) < 3:
        return
    mass = np.array([c[0] for c in columns])
    apparent = np.array([c[3]["apparent"] for c in columns])
    s, se, residual = fit_saturation(mass, apparent)
    _, density, fraction, tallest = columns[-1]
    bulk = density * fraction
    length = s / (bulk * args.side**2)
    mobilised = tallest["shear"] / tallest["normal"]
    print(f"M_sat = {s:.5f} +- {se:.5f} kg; largest residual {np.max(np.abs(residual)) / s:.3f} "
          f"of M_sat")
    print(f"tallest column: solid fraction {fraction:.4f}, rho_b = {bulk:.1f} kg/m^3, "
          f"mu_mob = {mobilised:.4f}")
    print(f"lambda = M_sat / (rho_b L^2) = {length:.5f} m = {length / args.side:.3f} L; "
          f"mu_mob K = L / (4 lambda) = {args.side / (4 * length):.4f}; "
          f"K = {args.side / (4 * mobilised * length):.3f}")


if __name__ == "__main__":
    main()
