#!/usr/bin/python3
"""Checks scripts/repose_angle.py on synthetic heaps whose surface is known exactly: in each of
eight sectors one sphere tops every diameter-wide bin of the flank at the height of a cone
(30 degrees in four sectors, 34 in the other four) over buried spheres; the script must give
each sector's angle and the angle of the mean slope, from an HDF5 snapshot and from a
LIGGGHTS dump (its last frame), and exit 2 on a file that is neither.

Usage: check_repose_angle.py SOURCE_DIR WORK_DIR
"""
import math
import os
import re
import subprocess
import sys

import h5py
import numpy as np

R = 2e-3
HEIGHT = 0.1
SECTORS = 8


def heap():
    """Positions and radii: the surface spheres of each sector, and a buried layer under them."""
    width = 2 * R
    positions = []
    for s in range(SECTORS):
        angle = 30.0 if s < SECTORS // 2 else 34.0
        slope = math.tan(math.radians(angle))
        phi = -math.pi + (s + 0.5) * 2 * math.pi / SECTORS  # the sector's middle
        for b in range(int(HEIGHT / slope / width)):
            rho = (b + 0.5) * width
            top = HEIGHT - slope * rho
            if top < 2 * R:
                break
            for depth in (0.0, 0.3 * top):  # the surface sphere, and one buried below it
                positions.append((rho * math.cos(phi), rho * math.sin(phi), top - R - depth))
    return np.array(positions), np.full(len(positions), R)


def run(script, *args):
    return subprocess.run([sys.executable, script, *args], capture_output=True, text=True)


def check_output(result, what):
    if result.returncode != 0:
        sys.exit(f"{what}: exit {result.returncode}\n{result.stderr}")
    sectors = [float(a) for a in re.search(r"sector angles \[deg\]: (.*)", result.stdout)
               .group(1).split()]
    expected = [30.0] * (SECTORS // 2) + [34.0] * (SECTORS // 2)
    if any(abs(a - e) > 1e-3 for a, e in zip(sectors, expected)) or len(sectors) != SECTORS:
        sys.exit(f"{what}: sector angles {sectors}, expected {expected}")
    mean = float(re.search(r"angle of repose ([0-9.]+)", result.stdout).group(1))
    slope = 0.5 * (math.tan(math.radians(30)) + math.tan(math.radians(34)))
    if abs(mean - math.degrees(math.atan(slope))) > 0.006:
        sys.exit(f"{what}: angle {mean}, expected {math.degrees(math.atan(slope)):.3f}")


def main():
    source, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    script = os.path.join(source, "scripts", "repose_angle.py")
    positions, radii = heap()
    snapshot = f"{work}/heap.h5"
    with h5py.File(snapshot, "w") as f:
        f["position"] = positions
        f["radius"] = radii
    check_output(run(script, snapshot), "HDF5 snapshot")
    dump = f"{work}/heap.dump"
    with open(dump, "w") as f:
        for step, shift in ((0, 0.05), (1000, 0.0)):  # a first frame 5 cm higher, then the heap
            f.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{len(radii)}\n"
                    "ITEM: BOX BOUNDS ff ff ff\n-1 1\n-1 1\n-1 1\nITEM: ATOMS id x y z radius\n")
            for k, (x, y, z) in enumerate(positions, start=1):
                f.write(f"{k} {x:.17g} {y:.17g} {z + shift:.17g} {R:.17g}\n")
    check_output(run(script, dump), "LIGGGHTS dump")
    with open(f"{work}/junk.txt", "w") as f:
        f.write("not a heap\n")
    for args, what in (([f"{work}/junk.txt"], "a text file"), ([f"{work}/missing.h5"], "no file"),
                       ([snapshot, "--sectors", "1"], "--sectors 1")):
        if run(script, *args).returncode != 2:
            sys.exit(f"{what}: expected exit status 2")
    print("repose_angle.py: sector angles and the mean slope recovered from HDF5 and dump files")


if __name__ == "__main__":
    main()
