#!/usr/bin/python3
"""Particle files of the side-by-side runs (scripts/peers/compare.sh), and their observables.

  particles.py csv SNAPSHOT.h5 OUT.csv
      the particles of a gpudem-mpi snapshot or checkpoint as a CSV source (x,y,z,r,vx,vy,vz)
  particles.py data IN OUT.data --style liggghts|lammps --density RHO --box X0 X1 Y0 Y1 Z0 Z1
      the particles of a CSV source, or of a bed, checkpoint or snapshot (HDF5), with their
      spins (a CSV's wx, wy, wz columns), as a data file: LIGGGHTS atom_style granular,
      LAMMPS atom_style sphere (atom type 1; LIGGGHTS' type 2 is left to the walls)
  particles.py observe FILE --density RHO --area A
      from a gpudem-mpi HDF5 file or a LAMMPS/LIGGGHTS text dump (id x y z radius vx vy vz
      omegax omegay omegaz): particles, bed height (highest top) [m], packing fraction (solid
      volume of the spheres whose centres lie in the lower half of the bed, over that half's
      volume), kinetic energy (translational and rotational) [J], as one CSV line
  particles.py slot SOURCE OUT.csv --plate X Y0 Y1 Z0 Z1 [--thickness T]
      the particles of SOURCE (as for data) with their spins as a CSV source, less those that
      touch the plate: the box X - T <= x <= X, Y0 <= y <= Y1, Z0 <= z <= Z1 (T = 0: the
      rectangle in the plane x = X)
  particles.py plate OUT.stl --plate X Y0 Y1 Z0 Z1
      that rectangle as an ASCII STL of two triangles
  particles.py force FILE --column NAME --from T
      mean and standard deviation of column NAME over the rows with time >= T, as one CSV
      line, from a CSV with a header (gpudem-mpi's timeseries.csv) or a whitespace-separated
      text file whose first line names the columns (a peer's fix print); both need a column
      "time"
"""
import argparse
import sys

import numpy as np


def read_h5(path):
    """(x, y, z, r), velocity, spin of a snapshot (position, radius, velocity) or of a
    checkpoint or bed (position_radius, velocity_inv_mass), in id order."""
    import h5py
    with h5py.File(path, "r") as f:
        if "position_radius" in f:
            xr = np.asarray(f["position_radius"], dtype=float)
            v = np.asarray(f["velocity_inv_mass"], dtype=float)[:, :3]
        else:
            xr = np.column_stack([np.asarray(f["position"], dtype=float),
                                  np.asarray(f["radius"], dtype=float)])
            v = np.asarray(f["velocity"], dtype=float)
        w = (np.asarray(f["angular_velocity"], dtype=float) if "angular_velocity" in f
             else np.zeros((len(xr), 3)))
        order = np.argsort(np.asarray(f["id"]))
    return xr[order], v[order], w[order]


def read_dump(path):
    """The last frame of a text dump whose columns are id x y z radius vx vy vz ox oy oz."""
    with open(path) as f:
        lines = f.read().splitlines()
    start = max(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    rows = np.array([[float(x) for x in line.split()] for line in lines[start + 1:] if line])
    rows = rows[np.argsort(rows[:, 0])]
    return rows[:, 1:5], rows[:, 5:8], rows[:, 8:11]


def write_csv(args):
    xr, v, _ = read_h5(args.snapshot)
    np.savetxt(args.out, np.column_stack([xr, v]), delimiter=",", fmt="%.17g",
               header="x,y,z,r,vx,vy,vz", comments="")


def read_particles(path):
    """(x, y, z, r), velocity, spin of an HDF5 file, a CSV source (zero where it has no
    vx, vy, vz or wx, wy, wz column) or a text dump."""
    if path.endswith(".h5"):
        return read_h5(path)
    if path.endswith(".csv"):
        c = read_table(path)
        zero = np.zeros(len(c["x"]))
        return (np.column_stack([c["x"], c["y"], c["z"], c["r"]]),
                np.column_stack([c.get(k, zero) for k in ("vx", "vy", "vz")]),
                np.column_stack([c.get(k, zero) for k in ("wx", "wy", "wz")]))
    return read_dump(path)


def write_data(args):
    xr, v, w = read_particles(args.source)
    types = 2 if args.style == "liggghts" else 1
    box = args.box
    with open(args.out, "w") as out:
        out.write(f"{args.style} data file of {args.source}\n\n{len(xr)} atoms\n"
                  f"{types} atom types\n\n")
        for lo, hi, axis in zip(box[0::2], box[1::2], "xyz"):
            out.write(f"{lo:.17g} {hi:.17g} {axis}lo {axis}hi\n")
        out.write("\nAtoms\n\n")
        for i, (x, y, z, r) in enumerate(xr, start=1):
            out.write(f"{i} 1 {2 * r:.17g} {args.density:.17g} {x:.17g} {y:.17g} {z:.17g}\n")
        out.write("\nVelocities\n\n")
        for i, row in enumerate(np.hstack([v, w]), start=1):
            out.write(f"{i} " + " ".join(f"{value:.17g}" for value in row) + "\n")


def observe(args):
    xr, v, w = read_particles(args.file)
    r = xr[:, 3]
    mass = args.density * 4 / 3 * np.pi * r ** 3
    inertia = 0.4 * mass * r ** 2
    height = float(np.max(xr[:, 2] + r))
    lower = xr[:, 2] < height / 2
    packing = float(np.sum(4 / 3 * np.pi * r[lower] ** 3) / (args.area * height / 2))
    kinetic = float(0.5 * np.sum(mass * np.sum(v * v, axis=1)) +
                    0.5 * np.sum(inertia * np.sum(w * w, axis=1)))
    print(f"{len(r)},{height:.6g},{packing:.6g},{kinetic:.6g}")


def plate_corners(plate):
    x, y0, y1, z0, z1 = plate
    return [(x, y0, z0), (x, y1, z0), (x, y1, z1), (x, y0, z1)]


def touches_plate(xr, plate, thickness):
    """Whether each sphere (x, y, z, r) reaches the box X - thickness <= x <= X, Y0 <= y <= Y1,
    Z0 <= z <= Z1 of `plate` (X, Y0, Y1, Z0, Z1)."""
    x, y0, y1, z0, z1 = plate
    dx = np.maximum(np.maximum(x - thickness - xr[:, 0], xr[:, 0] - x), 0.0)
    dy = np.maximum(np.maximum(y0 - xr[:, 1], xr[:, 1] - y1), 0.0)
    dz = np.maximum(np.maximum(z0 - xr[:, 2], xr[:, 2] - z1), 0.0)
    return dx ** 2 + dy ** 2 + dz ** 2 < xr[:, 3] ** 2


def write_slot(args):
    xr, v, w = read_particles(args.source)
    keep = ~touches_plate(xr, args.plate, args.thickness)
    np.savetxt(args.out, np.column_stack([xr, v, w])[keep], delimiter=",", fmt="%.17g",
               header="x,y,z,r,vx,vy,vz,wx,wy,wz", comments="")
    print(f"{int(np.sum(~keep))} of {len(xr)} particles touch the plate and are left out",
          file=sys.stderr)


def write_plate(args):
    a, b, c, d = plate_corners(args.plate)
    with open(args.out, "w") as out:
        out.write("solid plate\n")
        for triangle in ((a, b, c), (a, c, d)):
            out.write("  facet normal 1 0 0\n    outer loop\n")
            for vertex in triangle:
                out.write("      vertex " + " ".join(f"{x:.9g}" for x in vertex) + "\n")
            out.write("    endloop\n  endfacet\n")
        out.write("endsolid plate\n")


def read_table(path):
    """The columns of a CSV or whitespace-separated file with a header line, by name."""
    with open(path) as f:
        header = f.readline().lstrip("#").strip()
        comma = "," in header
        names = header.split(",") if comma else header.split()
        rows = np.loadtxt(f, delimiter="," if comma else None, ndmin=2)
    return {name.strip(): rows[:, k] for k, name in enumerate(names)}


def force(args):
    columns = read_table(args.file)
    for name in ("time", args.column):
        if name not in columns:
            sys.exit(f"particles.py: {args.file} has no column {name!r}")
    values = columns[args.column][columns["time"] >= args.start - 1e-12]
    if len(values) == 0:
        sys.exit(f"particles.py: {args.file} has no row at time >= {args.start}")
    print(f"{len(values)},{np.mean(values):.6g},{np.std(values):.6g}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("csv")
    p.add_argument("snapshot")
    p.add_argument("out")
    p = sub.add_parser("data")
    p.add_argument("source")
    p.add_argument("out")
    p.add_argument("--style", choices=("liggghts", "lammps"), required=True)
    p.add_argument("--density", type=float, required=True)
    p.add_argument("--box", type=float, nargs=6, required=True)
    p = sub.add_parser("observe")
    p.add_argument("file")
    p.add_argument("--density", type=float, required=True)
    p.add_argument("--area", type=float, required=True)
    for name in ("slot", "plate"):
        p = sub.add_parser(name)
        if name == "slot":
            p.add_argument("source")
            p.add_argument("--thickness", type=float, default=0.0, metavar="T")
        p.add_argument("out")
        p.add_argument("--plate", type=float, nargs=5, required=True,
                       metavar=("X", "Y0", "Y1", "Z0", "Z1"))
    p = sub.add_parser("force")
    p.add_argument("file")
    p.add_argument("--column", required=True)
    p.add_argument("--from", dest="start", type=float, required=True, metavar="T")
    args = parser.parse_args(argv)
    {"csv": write_csv, "data": write_data, "observe": observe, "slot": write_slot,
     "plate": write_plate, "force": force}[args.command](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
