#!/usr/bin/python3
"""Checks scripts/clod_fragments.py on snapshots of a known bond graph, and its refusals.

    check_clod_fragments.py SOURCE_DIR WORK_DIR

Before: ids 1-2-3-4-5 in a chain closed into a loop (one fragment of 5) and 10-11 (one of 2).
After: 1-2, 4-5 and 10-11 (three of 2; particle 3 lost its bonds). The table must list size 2:
1 before, 3 after, and size 5: 1 before, 0 after; the summary lines the counts and the largest
fragments; the plot must exist. A run without bonds in its snapshots and one with a single
snapshot are refused with exit status 2. Exit 0 when all holds, 1 otherwise.
"""
import csv
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np


def write_snapshot(path, pairs):
    with h5py.File(path, "w") as f:
        f["position"] = np.zeros((1, 3))
        if pairs is not None:
            f["bonds/ids"] = np.array(pairs, dtype=np.uint64).reshape(-1, 2)


def run(script, folder):
    return subprocess.run([sys.executable, str(script), str(folder)], capture_output=True,
                          text=True)


def main():
    source, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    script = source / "scripts" / "clod_fragments.py"
    shutil.rmtree(work, ignore_errors=True)
    problems = []
    known = work / "known"
    known.mkdir(parents=True)
    write_snapshot(known / "particles_000000.h5",
                   [(1, 2), (2, 3), (3, 4), (4, 5), (1, 5), (10, 11)])
    write_snapshot(known / "particles_000001.h5", [(1, 2), (4, 5), (10, 11)])
    result = run(script, known)
    if result.returncode != 0:
        problems.append(f"known graph: exit {result.returncode}: {result.stderr}")
    else:
        with open(known / "fragments.csv") as f:
            rows = {int(r["size"]): (int(r["fragments_before"]), int(r["fragments_after"]))
                    for r in csv.DictReader(f)}
        if rows != {2: (1, 3), 5: (1, 0)}:
            problems.append(f"known graph: table {rows}, expected {{2: (1, 3), 5: (1, 0)}}")
        if "6 bonds, 2 fragments of 7 particles" not in result.stdout or \
                "3 bonds, 3 fragments of 6 particles" not in result.stdout or \
                "largest 5" not in result.stdout:
            problems.append(f"known graph: summary {result.stdout!r}")
        if not (known / "fragments.png").is_file():
            problems.append("known graph: no fragments.png")
    bare = work / "without_bonds"
    bare.mkdir()
    for k in range(2):
        write_snapshot(bare / f"particles_00000{k}.h5", None)
    single = work / "single"
    single.mkdir()
    write_snapshot(single / "particles_000000.h5", [(1, 2)])
    for label, folder, phrase in (("without bonds", bare, "bonds = true"),
                                  ("one snapshot", single, "fewer than two snapshots")):
        result = run(script, folder)
        if result.returncode != 2 or phrase not in result.stderr:
            problems.append(f"{label}: exit {result.returncode}, {result.stderr!r}")
    for p in problems:
        print(p)
    print(f"check_clod_fragments: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
