#!/usr/bin/python3
"""Checks scripts/make_cylinder_stl.py: every corner of the tube it writes lies on the circle of
its radius at its bottom or top, the triangles cover the lateral surface of the prism once
(their areas add up to N faces of width 2 R sin(pi/N)), every normal points to the axis, and the
shipped inputs/heap/cylinder.stl is the file it writes for R = 0.035 m, z from -0.005 to 0.2 m.

Usage: check_cylinder_stl.py SOURCE_DIR WORK_DIR
"""
import math
import os
import subprocess
import sys

from stl_binary import read_binary_stl


def check(path, radius, bottom, top, sides):
    problems = []
    area = 0.0
    for normal, corners in read_binary_stl(path):
        for x, y, z in corners:
            if abs(math.hypot(x, y) - radius) > 1e-6 or min(abs(z - bottom), abs(z - top)) > 1e-6:
                problems.append(f"corner ({x}, {y}, {z}) off the tube")
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = corners
        u, v = (bx - ax, by - ay, bz - az), (cx - ax, cy - ay, cz - az)
        n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
        area += 0.5 * math.sqrt(sum(c * c for c in n))
        mx, my = (ax + bx + cx) / 3, (ay + by + cy) / 3
        if n[0] * mx + n[1] * my >= 0 or normal[0] * mx + normal[1] * my >= 0:
            problems.append(f"triangle at ({mx:.4f}, {my:.4f}) faces away from the axis")
    expected = sides * 2 * radius * math.sin(math.pi / sides) * (top - bottom)
    if abs(area - expected) > 1e-5 * expected:
        problems.append(f"lateral area {area:.6g} m^2, expected {expected:.6g}")
    return problems


def main():
    source, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    script = os.path.join(source, "scripts", "make_cylinder_stl.py")
    failures = []
    for radius, bottom, top, sides in ((0.035, -0.005, 0.2, 64), (0.1, 0.0, 0.05, 7)):
        out = os.path.join(work, f"tube-{radius}-{sides}.stl")
        subprocess.run([sys.executable, script, out, "--radius", str(radius), "--bottom",
                        str(bottom), "--top", str(top), "--sides", str(sides)], check=True)
        failures += check(out, radius, bottom, top, sides)
    shipped = os.path.join(source, "inputs", "heap", "cylinder.stl")
    with open(shipped, "rb") as a, open(os.path.join(work, "tube-0.035-64.stl"), "rb") as b:
        if a.read() != b.read():
            failures.append("inputs/heap/cylinder.stl is not make_cylinder_stl.py's R 0.035, "
                            "z -0.005 to 0.2")
    for problem in failures:
        print(problem)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
