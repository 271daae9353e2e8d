#!/usr/bin/python3
"""Fragment sizes of bonded clods before and after a run.

    clod_fragments.py RUN_DIR [--out PREFIX]

RUN_DIR is the output folder of a run with `[output] bonds = true`. The bonds of its first and
last snapshot (group /bonds/, dataset ids) join particles into fragments: the connected groups
of particles that bonds hold together (a particle without a bond is no fragment). Writes
PREFIX.csv (default RUN_DIR/fragments): per fragment size in particles, the fragments of that
size before and after; and PREFIX.png: the fragments by size before and after, and the share of
the bonded particles in fragments of at most each size. Prints the counts, the median size by
particles and the largest fragment, before and after.
Exit status 0, or 2 with a message for a folder without snapshots or without bonds in them.
"""
import argparse
import csv
import pathlib
import sys

try:
    import h5py
    import numpy as np
except ImportError:
    sys.exit("clod_fragments.py needs h5py and numpy (Debian: python3-h5py, python3-numpy); "
             "run it with /usr/bin/python3")


def fail(message):
    print(f"clod_fragments.py: {message}", file=sys.stderr)
    sys.exit(2)


def fragment_sizes(pairs):
    """Sizes of the connected groups of the particles the id pairs join (union by size)."""
    parent, size = {}, {}

    def root(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in pairs:
        for x in (a, b):
            if x not in parent:
                parent[x], size[x] = x, 1
        ra, rb = root(a), root(b)
        if ra == rb:
            continue
        if size[ra] < size[rb]:
            ra, rb = rb, ra
        parent[rb] = ra
        size[ra] += size[rb]
    return sorted(size[x] for x in parent if root(x) == x)


def snapshot_bonds(path):
    """The (lower id, higher id) pairs of a snapshot's bonds."""
    with h5py.File(path, "r") as f:
        if "bonds/ids" not in f:
            fail(f"{path} holds no bonds: run the scene with [output] bonds = true")
        return [tuple(int(v) for v in row) for row in f["bonds/ids"][...]]


def median_by_particles(sizes):
    """The fragment size that the median bonded particle belongs to."""
    if not sizes:
        return 0
    cumulative = np.cumsum(sizes)
    return sizes[int(np.searchsorted(cumulative, cumulative[-1] / 2))]


def write_table(path, before, after):
    counts_before, counts_after = np.bincount(before or [0]), np.bincount(after or [0])
    largest = max(len(counts_before), len(counts_after))
    with open(path, "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["size", "fragments_before", "fragments_after"])
        for s in range(2, largest):
            b = counts_before[s] if s < len(counts_before) else 0
            a = counts_after[s] if s < len(counts_after) else 0
            if a or b:
                writer.writerow([s, int(b), int(a)])


def plot(path, before, after):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, (counts, shares) = plt.subplots(1, 2, figsize=(10, 4))
    top = max(before + after + [2])
    bins = np.arange(1.5, top + 1.5)
    counts.hist([before, after], bins=bins, label=["before", "after"])
    counts.set_xlabel("fragment size [particles]")
    counts.set_ylabel("fragments")
    counts.legend()
    for sizes, label in ((before, "before"), (after, "after")):
        if sizes:
            shares.step(sizes, np.cumsum(sizes) / np.sum(sizes), where="post", label=label)
    shares.set_xlabel("fragment size [particles]")
    shares.set_ylabel("share of bonded particles (cumulative)")
    shares.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=120)


def describe(label, sizes, bonds):
    largest = sizes[-1] if sizes else 0
    return (f"{label}: {bonds} bonds, {len(sizes)} fragments of {sum(sizes)} particles, "
            f"median size by particles {median_by_particles(sizes)}, largest {largest}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run_dir", type=pathlib.Path)
    parser.add_argument("--out", type=pathlib.Path)
    args = parser.parse_args()
    snapshots = sorted(args.run_dir.glob("particles_*.h5"))
    if len(snapshots) < 2:
        fail(f"{args.run_dir}: fewer than two snapshots (particles_*.h5)")
    first, last = snapshot_bonds(snapshots[0]), snapshot_bonds(snapshots[-1])
    before, after = fragment_sizes(first), fragment_sizes(last)
    prefix = args.out or args.run_dir / "fragments"
    write_table(prefix.with_suffix(".csv"), before, after)
    plot(prefix.with_suffix(".png"), before, after)
    print(describe(f"before ({snapshots[0].name})", before, len(first)))
    print(describe(f"after ({snapshots[-1].name})", after, len(last)))
    print(f"table {prefix.with_suffix('.csv')}, plot {prefix.with_suffix('.png')}")


if __name__ == "__main__":
    main()
