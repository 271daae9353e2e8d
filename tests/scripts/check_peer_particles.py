#!/usr/bin/python3
"""Checks scripts/peers/particles.py, the particle files and observables of
scripts/peers/compare.sh, on a lattice of known answers:
- `csv` writes a snapshot's particles in id order (the snapshot lists them shuffled);
- `data` writes LIGGGHTS (two atom types) and LAMMPS (one) data files with each sphere's
  diameter, density, position and velocity, from the CSV or, with the spins, from the
  snapshot;
- `observe` gives, from the snapshot and from the same particles as a text dump, the count,
  the bed height (highest top), the packing fraction of the lower half (the spheres whose
  centres lie below half the height, over that half's volume) and the kinetic energy
  sum(m v^2 / 2 + I w^2 / 2), all computed here by hand;
- `slot` leaves out exactly the 6 spheres that reach a plate, and the 12 that reach it made
  0.02 m thick (worked out by hand on the lattice), and keeps the others' velocities and
  spins; `plate` writes that rectangle as two triangles; `force` gives the mean and standard deviation of a column from a time on, in a
  CSV and in a whitespace-separated file.

Usage: check_peer_particles.py SOURCE_DIR WORK_DIR
"""
import math
import os
import subprocess
import sys

import h5py
import numpy as np

DENSITY = 2000.0
R = 0.01
AREA = 0.1 * 0.1


def lattice():
    """5 x 5 x 4 spheres of radius R touching on a cubic lattice, in a 0.1 m x 0.1 m bin."""
    g = np.arange(5) * 2 * R + R
    x, y, z = np.meshgrid(g, g, np.arange(4) * 2 * R + R, indexing="ij")
    xyz = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    n = len(xyz)
    v = np.column_stack([np.arange(n) * 1e-3, np.zeros(n), -np.ones(n) * 2e-3])
    w = np.column_stack([np.zeros(n), np.ones(n) * 0.5, np.zeros(n)])
    return xyz, v, w


def check_plate(script, work, snapshot, xyz, v, w):
    """`slot`, `plate` and `force` against answers worked out by hand."""
    failures = []
    # The plate x = 0.035, 0.021 <= y <= 0.059, 0 <= z <= 0.05 reaches the spheres of the
    # column x = 0.03 (0.005 away) with y in {0.03, 0.05} and z in {0.01, 0.03, 0.05}; y = 0.01
    # and 0.07 lie 0.011 > R from its edges, x = 0.05 lies 0.015 > R away.
    plate = ["--plate", "0.035", "0.021", "0.059", "0", "0.05"]
    slot = os.path.join(work, "slot.csv")
    subprocess.run(script + ["slot", snapshot, slot, *plate], check=True, capture_output=True)
    rows = np.loadtxt(slot, delimiter=",", skiprows=1)
    gone = ((np.isclose(xyz[:, 0], 3 * R) & np.isin(np.round(xyz[:, 1] / R), [3, 5]) &
             np.isin(np.round(xyz[:, 2] / R), [1, 3, 5])))
    if int(np.sum(gone)) != 6 or not np.array_equal(
            rows, np.column_stack([xyz, np.full(len(xyz), R), v, w])[~gone]):
        failures.append(f"slot: kept {len(rows)} rows, expected the {len(xyz) - 6} that do not "
                        "reach the plate, with their velocities and spins")
    # 0.02 thick, the box 0.015 <= x <= 0.035 also reaches the column x = 0.01 (0.005 away).
    subprocess.run(script + ["slot", snapshot, slot, *plate, "--thickness", "0.02"], check=True,
                   capture_output=True)
    thick = np.loadtxt(slot, delimiter=",", skiprows=1)
    gone |= (np.isclose(xyz[:, 0], R) & np.isin(np.round(xyz[:, 1] / R), [3, 5]) &
             np.isin(np.round(xyz[:, 2] / R), [1, 3, 5]))
    if int(np.sum(gone)) != 12 or not np.array_equal(
            thick, np.column_stack([xyz, np.full(len(xyz), R), v, w])[~gone]):
        failures.append(f"slot --thickness: kept {len(thick)} rows, expected {len(xyz) - 12}")
    stl = os.path.join(work, "plate.stl")
    subprocess.run(script + ["plate", stl, *plate], check=True)
    vertices = [tuple(float(c) for c in line.split()[1:]) for line in open(stl)
                if line.strip().startswith("vertex")]
    corners = {(0.035, 0.021, 0.0), (0.035, 0.059, 0.0), (0.035, 0.059, 0.05),
               (0.035, 0.021, 0.05)}
    if len(vertices) != 6 or set(vertices) != corners:
        failures.append(f"plate: vertices {vertices}")
    series = [(0.0, 9.0), (0.1, 1.0), (0.2, 2.0), (0.3, 6.0)]  # from 0.1: mean 3, std sqrt(14/3)
    for name, sep, head in (("series.csv", ",", "time,plate_fx"), ("series.txt", " ",
                                                                   "# time plate_fx")):
        path = os.path.join(work, name)
        with open(path, "w") as f:
            f.write(head + "\n" + "".join(f"{a}{sep}{b}\n" for a, b in series))
        out = subprocess.run(script + ["force", path, "--column", "plate_fx", "--from", "0.1"],
                             capture_output=True, text=True, check=True).stdout.split(",")
        if (int(out[0]) != 3 or abs(float(out[1]) - 3.0) > 1e-9 or
                abs(float(out[2]) - math.sqrt(14 / 3)) > 1e-5):
            failures.append(f"force of {name}: {out}")
    return failures


def main():
    source, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    script = [sys.executable, os.path.join(source, "scripts", "peers", "particles.py")]
    xyz, v, w = lattice()
    n = len(xyz)
    shuffle = np.random.default_rng(3).permutation(n)
    snapshot = os.path.join(work, "snapshot.h5")
    with h5py.File(snapshot, "w") as f:
        f["position"] = xyz[shuffle]
        f["radius"] = np.full(n, R)
        f["velocity"] = v[shuffle]
        f["angular_velocity"] = w[shuffle]
        f["id"] = np.arange(n, dtype=np.uint64)[shuffle]
    dump = os.path.join(work, "particles.dump")
    with open(dump, "w") as f:
        f.write(f"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n{n}\nITEM: ATOMS id x y z radius\n")
        f.write("ITEM: TIMESTEP\n10\nITEM: ATOMS id x y z radius vx vy vz omegax omegay omegaz\n")
        for i in shuffle:
            f.write(" ".join(str(c) for c in [i + 1, *xyz[i], R, *v[i], *w[i]]) + "\n")

    failures = []
    mass = DENSITY * 4 / 3 * math.pi * R ** 3
    height = 8 * R
    lower = np.sum(xyz[:, 2] < height / 2)  # the two lowest layers
    expected = [n, height, lower * 4 / 3 * math.pi * R ** 3 / (AREA * height / 2),
                0.5 * mass * np.sum(v * v) + 0.5 * 0.4 * mass * R ** 2 * np.sum(w * w)]
    for path in (snapshot, dump):
        out = subprocess.run(script + ["observe", path, "--density", str(DENSITY), "--area",
                                       str(AREA)], capture_output=True, text=True, check=True)
        got = [float(x) for x in out.stdout.strip().split(",")]
        for name, g, e in zip(("count", "height", "packing", "kinetic energy"), got, expected):
            if abs(g - e) > 1e-5 * abs(e):
                failures.append(f"{os.path.basename(path)}: {name} {g}, expected {e}")

    csv = os.path.join(work, "particles.csv")
    subprocess.run(script + ["csv", snapshot, csv], check=True)
    rows = np.loadtxt(csv, delimiter=",", skiprows=1)
    if not np.allclose(rows, np.column_stack([xyz, np.full(n, R), v]), rtol=0, atol=1e-15):
        failures.append("the CSV is not the particles in id order")
    for style, types in (("liggghts", 2), ("lammps", 1)):
        data = os.path.join(work, f"{style}.data")
        subprocess.run(script + ["data", csv, data, "--style", style, "--density",
                                 str(DENSITY), "--box", "0", "0.1", "0", "0.1", "0", "0.2"],
                       check=True)
        text = open(data).read()
        atoms = text.split("Atoms\n\n")[1].split("\n\nVelocities")[0].splitlines()
        first = [float(x) for x in atoms[0].split()]
        if f"{n} atoms\n{types} atom types" not in text or len(atoms) != n:
            failures.append(f"{style}: header or atom count wrong")
        if first != [1, 1, 2 * R, DENSITY, *xyz[0]]:
            failures.append(f"{style}: first atom {first}")
        velocity = text.split("Velocities\n\n")[1].splitlines()[n - 1].split()
        if [float(x) for x in velocity[1:4]] != list(v[n - 1]):
            failures.append(f"{style}: last velocity {velocity}")
    data = os.path.join(work, "from_snapshot.data")
    subprocess.run(script + ["data", snapshot, data, "--style", "liggghts", "--density",
                             str(DENSITY), "--box", "0", "0.1", "0", "0.1", "0", "0.2"], check=True)
    velocity = open(data).read().split("Velocities\n\n")[1].splitlines()[n - 1].split()
    if [float(x) for x in velocity[1:]] != [*v[n - 1], *w[n - 1]]:
        failures.append(f"from the snapshot: last velocity and spin {velocity}")
    failures += check_plate(script, work, snapshot, xyz, v, w)
    for f in failures:
        print("FAILED:", f)
    if not failures:
        print("peer particles: observables, CSV and data files as computed by hand")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
