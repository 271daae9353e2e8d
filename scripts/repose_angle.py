#!/usr/bin/python3
"""Measures the angle of repose of a conical heap from its particles.

The particles come from a gpudem-mpi snapshot (HDF5 with datasets `position` and `radius`),
a bed or checkpoint file (`position_radius`), or a LIGGGHTS dump (`dump custom` with the
columns id x y z radius, the last time step in the file is read). About the vertical axis
through (X, Y), the heap is cut into SECTORS equal sectors; in each, the flank is binned by the
distance rho from the axis in steps of one mean diameter, each bin's surface height is the
highest top z + r of its particles, and a least-squares line through the bins whose surface
lies between LOW and HIGH of the heap's height gives that sector's slope. The angle of repose
is atan of the mean slope, with the standard error of the sectors' spread; the angle of each
sector is printed too.

Usage: scripts/repose_angle.py FILE [--axis X Y] [--sectors N] [--low F] [--high F]
Exit 2 on bad input.
"""
import argparse
import math
import sys

import numpy as np


def fail(message):
    print(f"repose_angle.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_hdf5(path):
    import h5py

    with h5py.File(path, "r") as f:
        if "position_radius" in f:
            xr = np.asarray(f["position_radius"])
            return xr[:, :3], xr[:, 3]
        return np.asarray(f["position"]), np.asarray(f["radius"])


def read_dump(path):
    """The last frame of a LIGGGHTS/LAMMPS `dump custom` file with x y z radius columns."""
    with open(path) as f:
        lines = f.read().splitlines()
    atoms = [k for k, line in enumerate(lines) if line.startswith("ITEM: ATOMS")]
    counts = [k for k, line in enumerate(lines) if line.startswith("ITEM: NUMBER OF ATOMS")]
    if not atoms or not counts or counts[-1] > atoms[-1]:
        raise ValueError("not a dump file: no 'ITEM: NUMBER OF ATOMS' and 'ITEM: ATOMS' frame")
    header = lines[atoms[-1]].split()[2:]
    if not all(c in header for c in ("x", "y", "z", "radius")):
        raise ValueError("the ATOMS columns must include x y z radius")
    count = int(lines[counts[-1] + 1])
    rows = [line.split() for line in lines[atoms[-1] + 1:atoms[-1] + 1 + count]]
    if len(rows) != count or any(len(r) != len(header) for r in rows):
        raise ValueError(f"the last frame does not hold {count} rows of {len(header)} columns")
    data = np.array(rows, dtype=float)
    col = {name: k for k, name in enumerate(header)}
    return data[:, [col["x"], col["y"], col["z"]]], data[:, col["radius"]]


def read_particles(path):
    try:
        with open(path, "rb") as f:
            is_hdf5 = f.read(8) == b"\x89HDF\r\n\x1a\n"
        positions, radii = read_hdf5(path) if is_hdf5 else read_dump(path)
    except (OSError, KeyError, ValueError, IndexError) as e:
        fail(f"{path}: {e}")
    if len(radii) == 0:
        fail(f"{path}: no particles")
    return positions, radii


def sector_slope(rho, top, width, low, high):
    """Least-squares slope of the surface heights (bin maxima) between low and high."""
    bins = np.floor(rho / width).astype(int)
    centres, heights = [], []
    for b in np.unique(bins):
        chosen = bins == b
        centres.append((b + 0.5) * width)
        heights.append(top[chosen].max())
    centres, heights = np.array(centres), np.array(heights)
    flank = (heights >= low) & (heights <= high)
    if np.count_nonzero(flank) < 3:
        return None
    return np.polyfit(centres[flank], heights[flank], 1)[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file")
    parser.add_argument("--axis", type=float, nargs=2, default=[0.0, 0.0], metavar=("X", "Y"))
    parser.add_argument("--sectors", type=int, default=8)
    parser.add_argument("--low", type=float, default=0.2, help="flank from this fraction of "
                        "the heap height")
    parser.add_argument("--high", type=float, default=0.8, help="to this fraction")
    args = parser.parse_args()
    if args.sectors < 2 or not 0 <= args.low < args.high <= 1:
        fail("need --sectors >= 2 and 0 <= --low < --high <= 1")
    positions, radii = read_particles(args.file)
    dx, dy = positions[:, 0] - args.axis[0], positions[:, 1] - args.axis[1]
    rho = np.hypot(dx, dy)
    top = positions[:, 2] + radii
    height = top.max()
    width = 2 * radii.mean()
    sector = np.floor((np.arctan2(dy, dx) + math.pi) / (2 * math.pi) * args.sectors)
    sector = np.minimum(sector.astype(int), args.sectors - 1)
    slopes = []
    for s in range(args.sectors):
        chosen = sector == s
        slope = sector_slope(rho[chosen], top[chosen], width, args.low * height,
                             args.high * height)
        if slope is None:
            fail(f"sector {s}: fewer than 3 surface bins between {args.low} and {args.high} "
                 "of the heap height")
        slopes.append(-slope)
    slopes = np.array(slopes)
    angles = np.degrees(np.arctan(slopes))
    mean = math.degrees(math.atan(slopes.mean()))
    error = float(np.std(angles, ddof=1) / math.sqrt(len(angles)))
    print(f"{len(radii)} particles, heap height {height:.4f} m, mean diameter {width * 1e3:.3f} mm")
    print("sector angles [deg]: " + " ".join(f"{a:.2f}" for a in angles))
    print(f"angle of repose {mean:.2f} +- {error:.2f} deg")


if __name__ == "__main__":
    main()
