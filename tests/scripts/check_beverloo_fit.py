#!/usr/bin/python3
"""Checks scripts/beverloo_fit.py on synthetic discharges: a bed on a simple cubic lattice
(core solid fraction pi/6 exactly, whatever its size) and time series whose `removed` grows at
W = C rho_b sqrt(g) (D - k d)^{5/2} give back C and k and exit 0 for C and k inside the quoted
ranges, exit 1 for a C outside them, print the rates alone for three runs, and exit 2 on a bad
argument or a missing time series.

Usage: check_beverloo_fit.py SOURCE_DIR WORK_DIR
"""
import math
import os
import re
import subprocess
import sys

import h5py
import numpy as np

R = 2e-3          # lattice sphere radius [m]
DENSITY = 2500.0  # the script's default grain density [kg/m^3]
G = 9.81
DIAMETERS = (0.024, 0.028, 0.032, 0.036, 0.040)


def write_lattice_bed(path, n):
    """n^3 spheres of radius R, centres R + 2 R i on each axis."""
    axis = R + 2 * R * np.arange(n)
    x, y, z = np.meshgrid(axis, axis, axis, indexing="ij")
    xr = np.column_stack([x.ravel(), y.ravel(), z.ravel(), np.full(x.size, R)])
    with h5py.File(path, "w") as f:
        f["position_radius"] = xr


def write_runs(work, tag, c, k):
    """One discharge folder per diameter, `removed` exactly linear in time."""
    rho_b = math.pi / 6 * DENSITY
    mass = DENSITY * 4 / 3 * math.pi * R**3
    runs = []
    for d_orifice in DIAMETERS:
        w = c * rho_b * math.sqrt(G) * (d_orifice - k * 2 * R) ** 2.5
        folder = f"{work}/{tag}-{d_orifice}"
        os.makedirs(folder, exist_ok=True)
        with open(f"{folder}/timeseries.csv", "w") as f:
            f.write("time,step,removed\n")
            for n in range(81):
                t = 0.005 * n
                f.write(f"{t:.17g},{n},{w / mass * t:.17g}\n")
        runs.append(f"{d_orifice}={folder}")
    return runs


def run(script, *args):
    return subprocess.run([sys.executable, script, *args], capture_output=True, text=True)


def main():
    source, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    script = os.path.join(source, "scripts", "beverloo_fit.py")
    bed = f"{work}/lattice.h5"
    write_lattice_bed(bed, 14)
    result = run(script, bed, *write_runs(work, "inside", 0.6, 1.4))
    if result.returncode != 0:
        sys.exit(f"C = 0.6, k = 1.4: exit {result.returncode}, expected 0\n{result.stdout}"
                 f"{result.stderr}")
    fit = re.search(r"C = ([0-9.]+) ± ([0-9.]+), k = ([0-9.]+) ± ([0-9.]+)", result.stdout)
    if not fit or abs(float(fit.group(1)) - 0.6) > 1e-3 or abs(float(fit.group(3)) - 1.4) > 1e-2:
        sys.exit(f"expected C = 0.600, k = 1.40:\n{result.stdout}")
    phi = re.search(r"core solid fraction ([0-9.]+)", result.stdout)
    if not phi or abs(float(phi.group(1)) - math.pi / 6) > 1e-4:
        sys.exit(f"expected the core solid fraction pi/6 = {math.pi / 6:.4f}:\n{result.stdout}")
    outside = run(script, bed, *write_runs(work, "outside", 0.45, 1.4))
    if outside.returncode != 1:
        sys.exit(f"C = 0.45: exit {outside.returncode}, expected 1\n{outside.stdout}")
    three = run(script, bed, *write_runs(work, "inside", 0.6, 1.4)[:3])
    if three.returncode != 0 or "Beverloo fit" in three.stdout or three.stdout.count("W = ") != 3:
        sys.exit(f"three runs: expected their three rates and no fit\n{three.stdout}")
    for args, what in (([bed, "0.03"], "a run without '='"),
                       ([bed, "wide=" + work], "a diameter that is not a number"),
                       ([bed, *[f"{d}={work}/missing" for d in DIAMETERS]], "missing series")):
        code = run(script, *args).returncode
        if code != 2:
            sys.exit(f"{what}: exit {code}, expected 2")
    print("beverloo_fit.py: C, k and the core solid fraction recovered; verdicts and refusals right")


if __name__ == "__main__":
    main()
