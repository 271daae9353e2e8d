#!/usr/bin/python3
"""Checks scripts/make_orifice_stl.py: the plate it writes covers [0, L]^2 at z = 0 except a
hole of the area of a circle of diameter D at its centre, every triangle faces +z, and the
shipped inputs/silo/orifice.stl is the file it writes for L = 0.12 m, D = 0.032 m.

Usage: check_orifice_stl.py SOURCE_DIR WORK_DIR
"""
import math
import os
import subprocess
import sys

from stl_binary import read_binary_stl


def signed_area(tri):
    (ax, ay, _), (bx, by, _), (cx, cy, _) = tri
    return 0.5 * ((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))


def covers(tri, x, y):
    """Whether the point lies in the triangle (seen from above, counter-clockwise)."""
    for i in range(3):
        (ax, ay, _), (bx, by, _) = tri[i], tri[(i + 1) % 3]
        if (bx - ax) * (y - ay) - (by - ay) * (x - ax) < 0:
            return False
    return True


def check(path, side, diameter, sides):
    failures = []
    tris = [corners for _, corners in read_binary_stl(path)]
    if len(tris) != 2 * sides:
        failures.append(f"{len(tris)} triangles, expected {2 * sides}")
    zs = [v[2] for tri in tris for v in tri]
    if any(z != 0 for z in zs):
        failures.append("a corner off the plane z = 0")
    areas = [signed_area(tri) for tri in tris]
    if min(areas) <= 0:
        failures.append(f"a triangle facing down or degenerate (signed area {min(areas)})")
    hole = side**2 - sum(areas)
    if abs(hole / (math.pi * diameter**2 / 4) - 1) > 1e-5:
        failures.append(f"hole area {hole}, circle {math.pi * diameter**2 / 4}")
    xs = [v[0] for tri in tris for v in tri] + [v[1] for tri in tris for v in tri]
    if abs(min(xs)) > 1e-7 or abs(max(xs) - side) > 1e-7:
        failures.append(f"plate spans {min(xs)}..{max(xs)}, expected 0..{side}")
    inradius = 0.5 * diameter * math.sqrt(2 * math.pi / (sides * math.sin(2 * math.pi / sides)))
    inradius *= math.cos(math.pi / sides)
    outside = 0.5 * diameter * 1.01 / math.cos(math.pi / sides)
    n = 60
    for i in range(n):
        for j in range(n):
            x, y = side * (i + 0.37) / n, side * (j + 0.61) / n  # off the spokes
            r = math.hypot(x - side / 2, y - side / 2)
            hits = sum(covers(tri, x, y) for tri in tris)
            if r < 0.99 * inradius and hits:
                failures.append(f"({x:.4f}, {y:.4f}) in the hole is covered")
            if r > outside and hits != 1:
                failures.append(f"({x:.4f}, {y:.4f}) on the plate covered {hits} times")
    return failures


def main():
    source, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    script = os.path.join(source, "scripts", "make_orifice_stl.py")
    failures = []
    for side, diameter, sides in [(0.12, 0.032, 32), (0.5, 0.1, 8), (0.2, 0.17, 64)]:
        path = os.path.join(work, f"orifice_{side}_{diameter}_{sides}.stl")
        subprocess.run([sys.executable, script, path, "--side", str(side), "--diameter",
                        str(diameter), "--sides", str(sides)], check=True)
        failures += [f"L {side}, D {diameter}, {sides} sides: {f}"
                     for f in check(path, side, diameter, sides)]
    with open(os.path.join(work, "orifice_0.12_0.032_32.stl"), "rb") as made, \
            open(os.path.join(source, "inputs", "silo", "orifice.stl"), "rb") as shipped:
        if made.read() != shipped.read():
            failures.append("inputs/silo/orifice.stl is not make_orifice_stl.py's L 0.12, D 0.032")
    for f in failures[:20]:
        print(f)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
