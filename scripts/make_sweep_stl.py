#!/usr/bin/env python3
"""Writes the cultivator sweep tool, a closed triangle mesh, as a binary STL.

Usage: scripts/make_sweep_stl.py [OUT] [--subdivide N]   (default inputs/tillage/sweep.stl)

--subdivide N splits every triangle into N x N congruent ones (32 N^2 triangles: N = 25 gives
20,000, N = 40 gives 51,200): the same surface, tessellated as finely as a scanned tool. Points
on an edge are computed alike by both triangles that share it, so the fine mesh welds closed.

Coordinates in metres; the tool travels along +x; z is up; the nose of the sweep (its lowest,
foremost point) is the origin, so a scene places the tool at its working depth by the offset.

Sweep (a V-shaped duckfoot blade):
  width, wing tip to wing tip    0.300 m
  sweep angle                    35° between each cutting edge and the travel direction
                                 (70° included angle at the nose)
  wing width                     0.050 m, measured across the cutting edge in plan view
  lift angle                     20°: the blade's upper surface rises towards the back
  thickness                      0.006 m, below the upper surface
Shank: a straight vertical bar 0.025 m wide (y) and 0.050 m long (x) on the blade's centre line,
its rear face where the wings' inner edges meet (0.087 m behind the nose), from the blade's lower
surface (its bottom follows the lift angle) up to z = 0.6 m.
The blade is 20 triangles (upper and lower surfaces, six side walls), the shank 12.
"""
import argparse
import math
import struct

WIDTH = 0.300
SWEEP_DEG = 35.0
WING_WIDTH = 0.050
LIFT_DEG = 20.0
THICKNESS = 0.006
SHANK_WIDTH = 0.025
SHANK_LENGTH = 0.050
SHANK_TOP = 0.6


def lift(x, y):
    """Upper blade surface: z rises by tan(lift) per metre towards the back (−x)."""
    return (x, y, -x * math.tan(math.radians(LIFT_DEG)))


def blade_outline():
    """Plan view outline, counter-clockwise seen from above: nose, right tip, right inner tip,
    centre (where the inner edges meet), left inner tip, left tip."""
    s = math.radians(SWEEP_DEG)
    half = WIDTH / 2
    tip_back = half / math.tan(s)
    inward = (-math.sin(s), math.cos(s))  # across the right cutting edge, backwards/inwards
    nose = (0.0, 0.0)
    right_tip = (-tip_back, -half)
    right_inner = (right_tip[0] + WING_WIDTH * inward[0], right_tip[1] + WING_WIDTH * inward[1])
    # the inner edge, parallel to the cutting edge, meets the centre line y = 0
    centre_x = right_inner[0] - right_inner[1] / math.tan(s)
    centre = (centre_x, 0.0)
    left_inner = (right_inner[0], -right_inner[1])
    left_tip = (right_tip[0], -right_tip[1])
    return [nose, right_tip, right_inner, centre, left_inner, left_tip]


def blade_triangles():
    outline = blade_outline()
    top = [lift(x, y) for x, y in outline]
    n = (math.sin(math.radians(LIFT_DEG)), 0.0, math.cos(math.radians(LIFT_DEG)))  # up normal
    bottom = [(x - THICKNESS * n[0], y, z - THICKNESS * n[2]) for x, y, z in top]
    fan = [(0, 1, 2), (0, 2, 3), (0, 3, 4), (0, 4, 5)]  # two convex wings
    tris = [tuple(top[i] for i in f) for f in fan]
    tris += [(bottom[a], bottom[c], bottom[b]) for a, b, c in fan]  # facing down
    k = len(outline)
    for i in range(k):
        j = (i + 1) % k
        tris.append((top[i], bottom[i], bottom[j]))
        tris.append((top[i], bottom[j], top[j]))
    return tris, outline


def shank_triangles(x0, x1, half_width, top):
    """A bar over x0..x1, |y| <= half_width, from the blade's lower surface up to z = top."""
    y0, y1 = -half_width, half_width

    def base(x):
        return lift(x, 0)[2] - THICKNESS / math.cos(math.radians(LIFT_DEG))

    v = [(x0, y0, base(x0)), (x1, y0, base(x1)), (x1, y1, base(x1)), (x0, y1, base(x0)),
         (x0, y0, top), (x1, y0, top), (x1, y1, top), (x0, y1, top)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    tris = []
    for a, b, c, d in faces:  # outward, counter-clockwise seen from outside
        tris.append((v[a], v[b], v[c]))
        tris.append((v[a], v[c], v[d]))
    return tris


def subdivided(t, n):
    """Triangle t split into n x n congruent triangles. The point with barycentric weights
    (i, j, k)/n is (i a + j b + k c)/n; on an edge one weight is 0 and the sum is that of the
    two end points, the same whichever triangle of the edge computes it."""
    if n == 1:
        return [t]
    a, b, c = t

    def point(i, j):
        k = n - i - j
        return tuple((i * a[d] + j * b[d] + k * c[d]) / n for d in range(3))

    tris = []
    for i in range(n):
        for j in range(n - i):
            tris.append((point(i + 1, j), point(i, j + 1), point(i, j)))
            if i + j < n - 1:
                tris.append((point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)))
    return tris


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    ux, uy, uz = bx - ax, by - ay, bz - az
    vx, vy, vz = cx - ax, cy - ay, cz - az
    n = (uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx)
    length = math.sqrt(sum(c * c for c in n))
    return tuple(c / length for c in n)


def write_binary_stl(path, tris):
    with open(path, "wb") as f:
        f.write(b"gpudem-mpi cultivator sweep, metres".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", *normal(t)))
            for vertex in t:
                f.write(struct.pack("<3f", *vertex))
            f.write(struct.pack("<H", 0))


def main():
    parser = argparse.ArgumentParser(description="Writes the cultivator sweep as a binary STL.")
    parser.add_argument("out", nargs="?", default="inputs/tillage/sweep.stl")
    parser.add_argument("--subdivide", type=int, default=1, metavar="N",
                        help="split each triangle into N x N (default 1: 32 triangles)")
    args = parser.parse_args()
    if args.subdivide < 1:
        parser.error(f"--subdivide must be 1 or more, not {args.subdivide}")
    tris, outline = blade_triangles()
    centre_x = outline[3][0]
    tris += shank_triangles(centre_x, centre_x + SHANK_LENGTH, SHANK_WIDTH / 2, SHANK_TOP)
    tris = [fine for t in tris for fine in subdivided(t, args.subdivide)]
    out = args.out
    write_binary_stl(out, tris)
    xs = [v[0] for t in tris for v in t]
    print(f"{out}: {len(tris)} triangles, x from {min(xs):.4f} to {max(xs):.4f} m")


if __name__ == "__main__":
    main()
