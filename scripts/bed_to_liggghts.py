#!/usr/bin/python3
"""Writes the particles of a bed or checkpoint file (HDF5) as a LIGGGHTS data file for
atom_style granular (id, type, diameter, density, x, y, z, then velocities and spins), in a
box given on the command line. Every grain is atom type 1 and has the one density given (a bed
of one material); type 2 is left to the walls.

Usage: scripts/bed_to_liggghts.py BED_H5 OUT.data --density RHO --box XLO XHI YLO YHI ZLO ZHI
"""
import argparse

import h5py
import numpy as np


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bed")
    parser.add_argument("out")
    parser.add_argument("--density", type=float, required=True, help="grain density [kg/m^3]")
    parser.add_argument("--box", type=float, nargs=6, required=True,
                        metavar=("XLO", "XHI", "YLO", "YHI", "ZLO", "ZHI"))
    args = parser.parse_args()
    with h5py.File(args.bed, "r") as f:
        xr = np.asarray(f["position_radius"])
        v = np.asarray(f["velocity_inv_mass"])[:, :3]
        w = np.asarray(f["angular_velocity"])
    box = args.box
    with open(args.out, "w") as out:
        out.write(f"LIGGGHTS data file of {args.bed}\n\n{len(xr)} atoms\n2 atom types\n\n")
        for lo, hi, axis in zip(box[0::2], box[1::2], "xyz"):
            out.write(f"{lo:.17g} {hi:.17g} {axis}lo {axis}hi\n")
        out.write("\nAtoms\n\n")
        for i, (x, y, z, r) in enumerate(xr, start=1):
            out.write(f"{i} 1 {2 * r:.17g} {args.density:.17g} {x:.17g} {y:.17g} {z:.17g}\n")
        out.write("\nVelocities\n\n")
        for i, row in enumerate(np.hstack([v, w]), start=1):
            out.write(f"{i} " + " ".join(f"{value:.17g}" for value in row) + "\n")


if __name__ == "__main__":
    main()
