#!/usr/bin/env python3
"""Writes a silo floor with a round orifice as a binary STL: a flat square plate in the plane
z = 0 with a regular polygonal hole at its centre.

Usage: scripts/make_orifice_stl.py OUT --side L --diameter D [--sides N]

Coordinates in metres. The plate covers [0, L] x [0, L]; the hole is centred at (L/2, L/2).
Its N-gon (default 32, a multiple of 8, so that the plate's corners lie on its spokes) has
the area of a circle of diameter D: circumradius D/2 · sqrt(2π / (N sin(2π/N))). Each edge of
the polygon and the stretch of the plate's outline on the same two spokes (every spoke i runs
from the polygon's corner at angle 2πi/N out to the square) make one quadrilateral, two
triangles; the corners are ordered so that every normal points up (+z), towards the grains.
"""
import argparse
import math

from stl_file import write_binary_stl


def hole_circumradius(diameter, sides):
    """Circumradius of the regular N-gon whose area equals that of a circle of this diameter."""
    return 0.5 * diameter * math.sqrt(2 * math.pi / (sides * math.sin(2 * math.pi / sides)))


def plate_triangles(side, diameter, sides):
    centre = 0.5 * side
    radius = hole_circumradius(diameter, sides)
    inner, outer = [], []
    for i in range(sides):
        angle = 2 * math.pi * i / sides
        c, s = math.cos(angle), math.sin(angle)
        inner.append((centre + radius * c, centre + radius * s, 0.0))
        reach = 0.5 * side / max(abs(c), abs(s))  # from the centre to the square along the spoke
        outer.append((centre + reach * c, centre + reach * s, 0.0))
    triangles = []
    for i in range(sides):
        j = (i + 1) % sides
        # counter-clockwise seen from above: normals along +z
        triangles.append((inner[i], outer[i], outer[j]))
        triangles.append((inner[i], outer[j], inner[j]))
    return triangles


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--side", type=float, required=True, help="plate edge L [m]")
    parser.add_argument("--diameter", type=float, required=True, help="orifice diameter D [m]")
    parser.add_argument("--sides", type=int, default=32, help="polygon sides, a multiple of 8")
    args = parser.parse_args()
    if args.sides < 8 or args.sides % 8:
        parser.error("--sides must be a multiple of 8")
    if not 0 < args.diameter < 0.9 * args.side:
        parser.error("--diameter must lie in (0, 0.9 L)")
    write_binary_stl(args.out, "silo floor with an orifice",
                     plate_triangles(args.side, args.diameter, args.sides))


if __name__ == "__main__":
    main()
