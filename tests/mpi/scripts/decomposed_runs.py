#!/usr/bin/python3
"""Runs scenes on several MPI ranks and checks that the decomposition changes nothing.

    decomposed_runs.py --binary B --mpirun M --work DIR CASE

CASE is one of:
  same-physics  tests/mpi/scenes/settle.toml at N = 1 and then at N = 2, 3, 4 with slabs, 2 x 2
                blocks, a periodic axis cut into 2 and 4 blocks, "auto" dims and METIS: the
                particle count and id set are identical and the final positions, velocities,
                spins and forces are equal bit for bit (every force sum runs in partner-id
                order, so the summation order does not depend on the ranks); the kinetic-energy
                series agree to 1e-12 relative (their sums do run in another order).
  restart       the same scene run straight at N = 1 against a run checkpointed half-way at
                N = 3 or 4 and continued at N = 2 or 1: final states equal bit for bit.
  balance       tests/mpi/scenes/corner.toml (a bed settling into one end of a channel, on
                2 x 2 blocks) with and without rebalancing: without, the final imbalance
                (max/mean particles per rank, time-series column "imbalance") is above 1.3;
                with rebalance_every = 0.01 s it is below 1.2, for the grid and for METIS, and
                the final states equal the unbalanced run's bit for bit.
  momentum      tests/mpi/scenes/periodic_gas.toml (closed periodic box, no gravity) at N = 4:
                total momentum conserved to 1e-12 of the total |momentum|, and the final state
                equal to N = 1 bit for bit.
Exit status 0 when all holds, 1 with one line per failure otherwise.
"""
import argparse
import csv
import os
import pathlib
import shutil
import subprocess
import sys

try:
    import h5py
    import numpy as np
except ImportError:
    sys.exit("decomposed_runs.py needs h5py and numpy (Debian: python3-h5py); use /usr/bin/python3")

SCENES = pathlib.Path(__file__).resolve().parent.parent / "scenes"
FIELDS = ("position", "radius", "velocity", "angular_velocity", "force")


class Runner:
    def __init__(self, binary, mpirun, work):
        self.binary, self.mpirun, self.work = binary, mpirun, pathlib.Path(work)
        self.failures = []

    def run(self, name, scene, ranks, *settings, restart=None):
        """Runs `scene` on `ranks` ranks into work/name and returns that folder."""
        out = self.work / name
        command = [self.mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks),
                   self.binary, str(scene), "--quiet", "--output-dir", str(out)]
        for s in settings:
            command += ["--set", s]
        if restart:
            command += ["--restart", str(restart)]
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f"{name}: exit {result.returncode}\n{result.stdout}{result.stderr}")
        return out

    def fail(self, line):
        self.failures.append(line)


def last_snapshot(out):
    files = sorted(pathlib.Path(out).glob("particles_*.h5"))
    if not files:
        sys.exit(f"{out}: no snapshot")
    return files[-1]


def read_by_id(path):
    """The snapshot's fields as arrays sorted by particle id."""
    with h5py.File(path, "r") as f:
        ids = f["id"][...]
        order = np.argsort(ids, kind="stable")
        fields = {name: f[name][...][order] for name in FIELDS if name in f}
        return ids[order], fields


def compare_states(runner, label, reference, candidate):
    ids_a, a = read_by_id(last_snapshot(reference))
    ids_b, b = read_by_id(last_snapshot(candidate))
    if len(ids_a) != len(ids_b) or not np.array_equal(ids_a, ids_b):
        runner.fail(f"{label}: particle ids differ ({len(ids_a)} against {len(ids_b)})")
        return
    for name in FIELDS:
        if name not in a:
            continue
        if not np.array_equal(a[name], b[name]):
            worst = np.max(np.abs(a[name] - b[name]))
            runner.fail(f"{label}: {name} not bitwise equal (largest difference {worst:.3e})")


def series(out):
    with open(pathlib.Path(out) / "timeseries.csv") as f:
        return list(csv.DictReader(f))


def compare_series(runner, label, reference, candidate):
    a, b = series(reference), series(candidate)
    if len(a) != len(b):
        runner.fail(f"{label}: {len(a)} time-series rows against {len(b)}")
        return
    for row_a, row_b in zip(a, b):
        for key in ("particles", "contacts"):
            if row_a[key] != row_b[key]:
                runner.fail(f"{label}: {key} differ at step {row_a['step']}")
                return
        for key in ("kinetic_translational", "kinetic_rotational"):
            x, y = float(row_a[key]), float(row_b[key])
            if abs(x - y) > 1e-12 * max(abs(x), abs(y), 1e-300):
                runner.fail(f"{label}: {key} {x!r} against {y!r} at step {row_a['step']}")
                return


def same_physics(runner):
    scene = SCENES / "settle.toml"
    reference = runner.run("n1", scene, 1)
    cases = [
        ("slabs_n2", 2, "decomposition.dims=[2,1,1]"),
        ("slabs_n3", 3, "decomposition.dims=[3,1,1]"),
        ("blocks_2x2", 4, "decomposition.dims=[2,2,1]"),
        ("periodic_y_n2", 2, "decomposition.dims=[1,2,1]"),
        ("periodic_y_n4", 4, "decomposition.dims=[1,4,1]"),
        ("auto_n4", 4, 'decomposition.dims="auto"'),
        ("metis_n3", 3, 'decomposition.method="metis"'),
        ("metis_n4", 4, 'decomposition.method="metis"'),
    ]
    for name, ranks, setting in cases:
        out = runner.run(name, scene, ranks, setting)
        compare_states(runner, name, reference, out)
        compare_series(runner, name, reference, out)


def restart(runner):
    scene = SCENES / "settle.toml"
    reference = runner.run("straight_n1", scene, 1)
    half = ["simulation.end_time=0.06", "checkpoint.every=0.06"]
    for first, second in ((3, 2), (4, 1)):
        name = f"restart_n{first}_n{second}"
        out = runner.run(name, scene, first, *half)
        checkpoint = out / "checkpoint.h5"
        runner.run(name, scene, second, restart=checkpoint)
        compare_states(runner, name, reference, out)


def final_imbalance(out):
    return float(series(out)[-1]["imbalance"])


def balance(runner):
    scene = SCENES / "corner.toml"
    blocks = "decomposition.dims=[2,2,1]"
    fixed = runner.run("fixed_blocks", scene, 4, blocks)
    worst = final_imbalance(fixed)
    print(f"fixed blocks: final imbalance {worst:.3f}")
    if not worst > 1.3:
        runner.fail(f"fixed blocks: imbalance {worst:.3f}, the scene no longer unbalances them")
    rebalance = "decomposition.rebalance_every=0.01"
    metis = 'decomposition.method="metis"'
    for name, method in (("rebalanced_blocks", blocks), ("rebalanced_metis", metis)):
        out = runner.run(name, scene, 4, rebalance, method)
        value = final_imbalance(out)
        print(f"{name}: final imbalance {value:.3f}")
        if not value < 1.2:
            runner.fail(f"{name}: final imbalance {value:.3f}, not below 1.2")
        compare_states(runner, name, fixed, out)


def momentum(runner):
    scene = SCENES / "periodic_gas.toml"
    reference = runner.run("gas_n1", scene, 1)
    out = runner.run("gas_n4", scene, 4)
    compare_states(runner, "gas_n4", reference, out)
    snapshots = sorted(out.glob("particles_*.h5"))
    totals = []
    for path in (snapshots[0], snapshots[-1]):
        with h5py.File(path, "r") as f:
            mass = 2500.0 * 4.0 / 3.0 * np.pi * f["radius"][...] ** 3
            p = mass[:, None] * f["velocity"][...]
            totals.append((p.sum(axis=0), np.abs(p).sum()))
    drift = np.max(np.abs(totals[1][0] - totals[0][0]))
    if not drift <= 1e-12 * totals[0][1]:
        runner.fail(f"gas_n4: momentum changed by {drift:.3e} (total |p| {totals[0][1]:.3e})")
    else:
        print(f"gas_n4: momentum change {drift:.3e} of total |p| {totals[0][1]:.3e}")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--binary", required=True)
    parser.add_argument("--mpirun", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("case", choices=["same-physics", "restart", "balance", "momentum"])
    args = parser.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    runner = Runner(args.binary, args.mpirun, args.work)
    cases = {"same-physics": same_physics, "restart": restart, "balance": balance,
             "momentum": momentum}
    cases[args.case](runner)
    for line in runner.failures:
        print(line)
    return 1 if runner.failures else 0


if __name__ == "__main__":
    sys.exit(main())
