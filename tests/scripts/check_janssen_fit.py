#!/usr/bin/python3
"""Checks scripts/janssen_fit.py on synthetic columns: beds of known mass and time series whose
floor loads follow M_sat (1 - exp(-M / M_sat)) exactly (plus a load before the averaging window
that the fit must ignore) give back M_sat, the mobilised friction S / N and K; a bad argument
and a time series without the wall columns exit with status 2.

Usage: check_janssen_fit.py SOURCE_DIR WORK_DIR
"""
import math
import os
import re
import subprocess
import sys

import h5py
import numpy as np

G = 9.81
SATURATION = 0.08  # kg
MU_MOB = 0.25
SIDE = 0.04


def write_bed(path, count, mass_each):
    """`count` spheres of r = 2 mm stacked along z, each of mass `mass_each`."""
    r = 2e-3
    z = r + 2 * r * np.arange(count) / 25  # 25 spheres a layer, in effect
    xr = np.column_stack([np.full(count, 0.02), np.full(count, 0.02), z, np.full(count, r)])
    v = np.zeros((count, 4))
    v[:, 3] = 1 / mass_each
    with h5py.File(path, "w") as f:
        f["position_radius"] = xr
        f["velocity_inv_mass"] = v


def write_series(path, mass, normal_each, columns=None):
    apparent = SATURATION * (1 - math.exp(-mass / SATURATION))
    shear_each = (mass - apparent) * G / 4
    names = columns or ["time", "floor_fz", "x0_fx", "x0_fz", "x1_fx", "x1_fz",
                        "y0_fy", "y0_fz", "y1_fy", "y1_fz"]
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for k in range(401):
            t = k * 0.001
            floor = -mass * G if t < 0.2 else -apparent * G  # hydrostatic before the window
            walls = [-normal_each, -shear_each, normal_each, -shear_each,
                     -normal_each, -shear_each, normal_each, -shear_each]
            f.write(",".join(f"{value:.17g}" for value in [t, floor] + walls) + "\n")


def run(script, *args):
    return subprocess.run([sys.executable, script, *args], capture_output=True, text=True)


def main():
    source, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    script = os.path.join(source, "scripts", "janssen_fit.py")
    runs = []
    for count in (400, 900, 1600, 2600, 4000):
        mass = count * 8.5e-5
        bed, folder = f"{work}/bed-{count}.h5", f"{work}/slide-{count}"
        os.makedirs(folder, exist_ok=True)
        write_bed(bed, count, 8.5e-5)
        apparent = SATURATION * (1 - math.exp(-mass / SATURATION))
        write_series(f"{folder}/timeseries.csv", mass, (mass - apparent) * G / (4 * MU_MOB))
        runs.append(f"{bed}={folder}")
    result = run(script, *runs)
    if result.returncode != 0:
        sys.exit(f"janssen_fit.py failed:\n{result.stderr}")
    out = result.stdout
    sat = float(re.search(r"M_sat = ([0-9.e+-]+) \+-", out).group(1))
    if abs(sat - SATURATION) > 1e-6 * SATURATION:
        sys.exit(f"M_sat {sat}, expected {SATURATION}\n{out}")
    mu = float(re.search(r"mu_mob = ([0-9.]+)\n", out).group(1))
    if abs(mu - MU_MOB) > 1e-4:
        sys.exit(f"mu_mob {mu}, expected {MU_MOB}\n{out}")
    # K = rho_b L^3 / (4 mu_mob M_sat), rho_b from the printed solid fraction and density
    rho_b = float(re.search(r"rho_b = ([0-9.]+) kg", out).group(1))
    k = float(re.search(r"K = ([0-9.]+)\n", out).group(1))
    expected_k = rho_b * SIDE**3 / (4 * MU_MOB * SATURATION)
    if abs(k - expected_k) > 2e-3 * expected_k:
        sys.exit(f"K {k}, expected {expected_k:.4f}\n{out}")
    for args, what in (([*runs[:2], "no-separator"], "a run without '='"),
                       (["--blocks", "1", *runs], "--blocks 1")):
        if run(script, *args).returncode != 2:
            sys.exit(f"{what}: expected exit status 2")
    write_series(f"{work}/slide-400/timeseries.csv", 0.034, 1.0,
                 ["time", "floor_fz", "a", "b", "c", "d", "e", "f", "g", "h"])
    if run(script, *runs).returncode != 2:
        sys.exit("a time series without the wall columns: expected exit status 2")
    print("janssen_fit.py: M_sat, mu_mob and K recovered; bad input refused")


if __name__ == "__main__":
    main()
