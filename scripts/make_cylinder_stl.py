#!/usr/bin/env python3
"""Writes an open cylinder (a tube without caps) as a binary STL: the lateral surface of a
regular N-gon prism about the z axis, for the lifting-cylinder heap of inputs/heap/.

Usage: scripts/make_cylinder_stl.py OUT --radius R --bottom Z0 --top Z1 [--sides N]

Coordinates in metres. The polygon's corners lie on the circle of radius R (its flat faces at
R cos(π/N) from the axis: 0.12 % inside for the default N = 64). Each face between corners i
and i + 1 is two triangles, ordered so that every normal points to the axis, towards the
grains inside.
"""
import argparse
import math

from stl_file import write_binary_stl


def tube_triangles(radius, bottom, top, sides):
    corners = [(radius * math.cos(2 * math.pi * i / sides),
                radius * math.sin(2 * math.pi * i / sides)) for i in range(sides)]
    triangles = []
    for i in range(sides):
        (x0, y0), (x1, y1) = corners[i], corners[(i + 1) % sides]
        a, b = (x0, y0, bottom), (x1, y1, bottom)
        c, d = (x1, y1, top), (x0, y0, top)
        # (b - a) x (c - a) points away from the axis; the reverse order points to it
        triangles.append((a, c, b))
        triangles.append((a, d, c))
    return triangles


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--radius", type=float, required=True, help="radius R [m]")
    parser.add_argument("--bottom", type=float, required=True, help="lower edge Z0 [m]")
    parser.add_argument("--top", type=float, required=True, help="upper edge Z1 [m]")
    parser.add_argument("--sides", type=int, default=64, help="polygon sides N >= 3")
    args = parser.parse_args()
    if args.radius <= 0 or args.top <= args.bottom or args.sides < 3:
        parser.error("need R > 0, Z1 > Z0 and N >= 3")
    write_binary_stl(args.out, "open cylinder",
                     tube_triangles(args.radius, args.bottom, args.top, args.sides))


if __name__ == "__main__":
    main()
