#!/usr/bin/python3
"""Runs scenes on several MPI ranks and checks that the decomposition changes nothing.

    decomposed_runs.py --binary B --mpirun M --work DIR CASE

CASE is one of:
  same-physics  tests/mpi/scenes/settle.toml at N = 1 and then at N = 2, 3, 4 with slabs, 2 x 2
                blocks, a periodic axis cut into 2 and 4 blocks, "auto" dims and METIS: the
                particle count and id set are identical and the final positions, velocities,
                spins and forces are equal bit for bit (no force sum depends on the ranks:
                the host sums pair loads as integers, CUDA in partner-id order); the kinetic-energy
                series agree to 1e-12 relative (their sums do run in another order). The same
                in the float precision policy at N = 3 slabs and 2 x 2 blocks against its N = 1.
  restart       the same scene run straight at N = 1 against a run checkpointed half-way at
                N = 3 or 4 and continued at N = 2 or 1: final states equal bit for bit; in the
                float policy, checkpointed at N = 3 and continued at N = 2, likewise.
  balance       tests/mpi/scenes/corner.toml (a bed settling into one end of a channel, on
                2 x 2 blocks) with and without rebalancing: without, the final imbalance
                (max/mean particles per rank, time-series column "imbalance") is above 1.3;
                with rebalance_every = 0.01 s it is below 1.2, for the grid and for METIS, and
                the final states equal the unbalanced run's bit for bit.
  momentum      tests/mpi/scenes/periodic_gas.toml (closed periodic box, no gravity) at N = 4:
                total momentum conserved to 1e-12 of the total |momentum|, and the final state
                equal to N = 1 bit for bit.
  sliding-pair  tests/mpi/scenes/sliding_pair.toml (two grains in one sliding contact, drifting
                across the cut of 2 slabs) at N = 1 and N = 2, a snapshot every step: position,
                velocity, spin and force of both grains equal bit for bit at every snapshot.
                Over the contact window the pair overlaps at every step, the left grain goes
                from the left slab to more than skin/2 into the right one (so the neighbour
                list, and with it the migration, is rebuilt mid-contact), the friction force is
                above 10 % of the normal force and the two forces are opposite (the contact is
                each grain's only force) to 1e-9 of the force. The N = 2 run writes its
                snapshots on a writer thread (its banner says so); again with
                output.asynchronous = false, every snapshot and particles.xmf are the same.
  leaving       tests/mpi/scenes/leaking_gas.toml (particles streaming across the cuts of a box
                open along x and z, many leaving it) at N = 1, 2 slabs, 4 slabs and 2 x 2
                blocks: final states equal bit for bit, and the particle count and removed
                count of every time-series row equal one rank's; between a fifth and four
                fifths of the particles are removed, in more than one row's interval.
  tiled         tests/mpi/scenes/tiled_pour.toml (20000 grains placed by 5 layers of tiles,
                each rank creating only its part of them) at N = 1 and at N = 2, 3 and 4 with
                "auto" dims and at 2 x 2 blocks: the particle ids are those of one rank and the
                final states equal bit for bit; the time series agree as in same-physics. The
                same for tests/mpi/scenes/layered_pour.toml (two overlapping layers placed by
                tiles, then stones placed sequentially among them) at N = 1, 3 and 4.
  killed-checkpoint
                tests/mpi/scenes/periodic_gas.toml checkpointed every step, alternately on 2
                and 3 ranks; each round is killed (SIGKILL to every process group of its
                session) at a random moment after its first new checkpoint, and restarts from
                the checkpoint. Read while the run goes and after each kill, the checkpoint
                always opens, holds every particle once and its step grows from round to
                round; a last restart on 2 ranks runs 3 more steps and exits 0.
  tool          tests/mpi/scenes/tool.toml (a small sweep mesh cutting a thin bed) at N = 1 and
                at N = 2 and 4 slabs along the travel and 2 x 2 blocks: final states equal bit
                for bit and the sweep's force and torque series equal to 1e-9 of their largest
                value (the rank sums run in another order; the CSV holds 10 digits); the
                sweep's largest |F_x| is above 0.5 N. A run checkpointed at t = 0.09 s on 3
                ranks, mid-cut, holds mesh contact springs, and continued on 2 ranks it ends
                equal bit for bit to the straight run; continued without those springs it
                does not.
  piston        tests/mpi/scenes/piston.toml (1000 grains poured under a loaded piston) at
                N = 1 and at N = 2 and 3 slabs across the piston's travel and 2 x 2 blocks:
                final states equal bit for bit and the piston's displacement and velocity
                series equal digit for digit. A run checkpointed at t = 0.06 s on 3 ranks,
                continued on 2, ends equal bit for bit to the straight run; continued from
                the checkpoint without the walls' motion it does not.
  adaptive      tests/mpi/scenes/tool.toml with dt = "adaptive" (the sweep cutting the bed,
                each base step split while the grains move fast) at N = 1 and at N = 2 slabs
                and 2 x 2 blocks: the step takes at least two values over the run, the final
                states equal bit for bit and the dt column digit for digit. A run
                checkpointed on 3 ranks at a base step split in substeps, after a list build
                inside a base step, continued on 2 ends equal bit for bit to the straight
                run; continuing it with dt = "auto" is refused (exit 2, simulation.dt).
  bed           tests/mpi/scenes/settle.toml as a bed preparation (settle, trim at 0.03 m, save)
                at N = 1 and 3: the two bed files hold the same particles and the same pair and
                wall springs (also of pairs split between ranks) bit for bit, and both runs
                print the same summary line with the counts over all ranks. Then
                tests/mpi/scenes/bed_start.toml starts from the N = 1 bed as its only source
                (each rank reads its part of the rows and springs) at N = 1, 2 and 3: the same
                final state bit for bit and the same time series; and so does
                tests/mpi/scenes/bed_topped.toml (the bed, then a layer placed by tiles that
                reaches into its top) at N = 1 and 3.
  cuda          tests/mpi/scenes/settle.toml on the CUDA backend (ranks sharing the one GPU) at
                N = 1, 2 slabs and 2 x 2 blocks, and leaking_gas.toml at N = 1 and 2 slabs: the
                final states equal N = 1 on the device bit for bit (and leaking_gas's particle
                counts at every row); against the host backend at N = 1, whose arithmetic
                rounds otherwise (fused multiply-adds), the final gravitational potential
                energy agrees within 1 % of the energy the fall released and the contact count
                within 5 %. Exits 77 (skipped) where this build has no CUDA backend or no
                device is visible.
Exit status 0 when all holds, 1 with one line per failure otherwise, 77 when skipped.
"""
import argparse
import csv
import os
import pathlib
import random
import shutil
import signal
import subprocess
import sys
import time
import tomllib

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
        self.banner = ""

    def command(self, name, scene, ranks, settings, restart=None, quiet=True, backend="host"):
        """The mpirun command line that runs `scene` on `ranks` ranks into work/name."""
        command = [self.mpirun, "--allow-run-as-root", "--oversubscribe", "-np", str(ranks),
                   self.binary, str(scene), "--output-dir", str(self.work / name),
                   "--backend", backend]
        if quiet:
            command.append("--quiet")
        for s in settings:
            command += ["--set", s]
        if restart:
            command += ["--restart", str(restart)]
        return command

    def run(self, name, scene, ranks, *settings, restart=None, quiet=True, backend="host"):
        """Runs `scene` on `ranks` ranks into work/name and returns that folder; the standard
        output (the banner unless quiet) is kept in self.banner."""
        command = self.command(name, scene, ranks, settings, restart, quiet, backend)
        result = subprocess.run(command, capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f"{name}: exit {result.returncode}\n{result.stdout}{result.stderr}")
        self.banner = result.stdout
        return self.work / name

    def run_raw(self, name, scene, ranks, *settings, restart=None):
        """Runs `scene` as run() does and returns the finished process, whatever its exit."""
        command = self.command(name, scene, ranks, settings, restart)
        return subprocess.run(command, capture_output=True, text=True)

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


def snapshot_differences(path_a, path_b):
    """Lines naming what differs between two snapshots: their particle ids, or each field that
    is not bitwise equal, with its largest difference."""
    ids_a, a = read_by_id(path_a)
    ids_b, b = read_by_id(path_b)
    if len(ids_a) != len(ids_b) or not np.array_equal(ids_a, ids_b):
        return [f"particle ids differ ({len(ids_a)} against {len(ids_b)})"]
    unequal = [name for name in FIELDS if name in a and not np.array_equal(a[name], b[name])]
    worst = {name: np.max(np.abs(a[name] - b[name])) for name in unequal}
    return [f"{name} not bitwise equal (largest difference {worst[name]:.3e})" for name in unequal]


def compare_states(runner, label, reference, candidate):
    for line in snapshot_differences(last_snapshot(reference), last_snapshot(candidate)):
        runner.fail(f"{label}: {line}")


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
    single = 'simulation.precision="float"'
    float_reference = runner.run("float_n1", scene, 1, single)
    for name, ranks, setting in (("float_slabs_n3", 3, "decomposition.dims=[3,1,1]"),
                                 ("float_blocks_2x2", 4, "decomposition.dims=[2,2,1]")):
        out = runner.run(name, scene, ranks, setting, single)
        compare_states(runner, name, float_reference, out)
        compare_series(runner, name, float_reference, out)


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
    single = 'simulation.precision="float"'
    float_reference = runner.run("float_straight_n1", scene, 1, single)
    out = runner.run("float_restart_n3_n2", scene, 3, *half, single)
    runner.run("float_restart_n3_n2", scene, 2, single, restart=out / "checkpoint.h5")
    compare_states(runner, "float_restart_n3_n2", float_reference, out)


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

def leaving(runner):
    scene = SCENES / "leaking_gas.toml"
    reference = runner.run("leaking_n1", scene, 1)
    rows = series(reference)
    start, removed = int(rows[0]["particles"]), int(rows[-1]["removed"])
    growing = sum(int(a["removed"]) < int(b["removed"]) for a, b in zip(rows, rows[1:]))
    print(f"leaking_n1: {removed} of {start} particles removed, in {growing} row intervals")
    if not (start / 5 < removed < 4 * start / 5 and growing > 1):
        runner.fail(f"leaking_n1: {removed} of {start} removed in {growing} row intervals; the "
                    "scene no longer removes a fifth to four fifths over several rows")
    for name, ranks, dims in (("leaking_slabs_n2", 2, "[2,1,1]"),
                              ("leaking_slabs_n4", 4, "[4,1,1]"),
                              ("leaking_blocks_2x2", 4, "[2,2,1]")):
        out = runner.run(name, scene, ranks, f"decomposition.dims={dims}")
        compare_states(runner, name, reference, out)
        compare_series(runner, name, reference, out)
        counts = [(r["particles"], r["removed"]) for r in series(out)]
        if counts != [(r["particles"], r["removed"]) for r in rows]:
            runner.fail(f"{name}: particle or removed counts differ from one rank's")

# ---- sliding-pair ---------------------------------------------------------------------------

# Steps of sliding_pair.toml during which the grains are in contact (it lasts from step 5 to 192;
# the dashpot dominates the first steps and the last, where |F_t| / |F_n| leaves [0.1, 1]).
SLIDING_WINDOW = range(10, 186)
FRICTION_SHARE = 0.1  # least |F_t| / |F_n| in the window
NEWTON_TOLERANCE = 1e-9  # largest |F_0 + F_1| / |F_1|: the contact is each grain's only force


def tiled(runner):
    scene = SCENES / "tiled_pour.toml"
    reference = runner.run("tiled_n1", scene, 1)
    for name, ranks, setting in (("tiled_auto_n2", 2, 'decomposition.dims="auto"'),
                                 ("tiled_auto_n3", 3, 'decomposition.dims="auto"'),
                                 ("tiled_auto_n4", 4, 'decomposition.dims="auto"'),
                                 ("tiled_blocks_2x2", 4, "decomposition.dims=[2,2,1]")):
        out = runner.run(name, scene, ranks, setting)
        compare_states(runner, name, reference, out)
        compare_series(runner, name, reference, out)
    layered = SCENES / "layered_pour.toml"
    reference = runner.run("layered_n1", layered, 1)
    for ranks in (3, 4):
        name = f"layered_n{ranks}"
        out = runner.run(name, layered, ranks, 'decomposition.dims="auto"')
        compare_states(runner, name, reference, out)
        compare_series(runner, name, reference, out)


def snapshots_by_step(out):
    """{step: snapshot path} of a run's folder."""
    steps = {}
    for path in sorted(pathlib.Path(out).glob("particles_*.h5")):
        with h5py.File(path, "r") as f:
            steps[int(f.attrs["step"])] = path
    return steps


def compare_every_snapshot(runner, label, reference, candidate):
    a, b = snapshots_by_step(reference), snapshots_by_step(candidate)
    if sorted(a) != sorted(b):
        runner.fail(f"{label}: snapshot steps differ ({len(a)} against {len(b)} snapshots)")
        return
    differing = [(step, lines) for step in sorted(a)
                 for lines in [snapshot_differences(a[step], b[step])] if lines]
    if differing:
        step, lines = differing[0]
        runner.fail(f"{label}: {len(differing)} of {len(a)} snapshots differ, the first at step "
                    f"{step}: {'; '.join(lines)}")
    else:
        print(f"{label}: all {len(a)} snapshots bitwise equal to one rank's")


def pair_contact(path):
    """Overlap, normal force F_n (on grain 1 along the centre line from grain 0), tangential force
    |F_t|, |F_0 + F_1|, the grains' x and the smallest radius of a sliding-pair snapshot."""
    _, s = read_by_id(path)
    x, r, force = s["position"], s["radius"], s["force"]
    distance = np.linalg.norm(x[1] - x[0])
    normal = (x[1] - x[0]) / distance
    f_n = float(np.dot(force[1], normal))
    f_t = float(np.linalg.norm(force[1] - f_n * normal))
    newton = float(np.linalg.norm(force[0] + force[1]))
    return r[0] + r[1] - distance, f_n, f_t, newton, x[0][0], x[1][0], r.min()


def check_sliding_window(runner, scene, out):
    """Over SLIDING_WINDOW the pair overlaps, starts on both sides of the cut, grain 0 ends more
    than skin/2 past it (a displacement that forces a neighbour-list rebuild, where it migrates),
    friction carries more than FRICTION_SHARE of |F_n|, and the contact is the only force."""
    with open(scene, "rb") as f:
        domain = tomllib.load(f)["domain"]
    cut = 0.5 * (domain["min"][0] + domain["max"][0])  # two coarse cells along x
    steps = snapshots_by_step(out)
    rows = [pair_contact(steps[step]) for step in SLIDING_WINDOW]
    overlap = min(row[0] for row in rows)
    share = min(row[2] / abs(row[1]) for row in rows)
    newton = max(row[3] / np.hypot(row[1], row[2]) for row in rows)
    start_0, start_1, end_0 = rows[0][4] - cut, rows[0][5] - cut, rows[-1][4] - cut
    half_skin = 0.25 * rows[0][6]  # the "auto" skin is half the smallest radius
    print(f"sliding pair, steps {SLIDING_WINDOW.start}-{SLIDING_WINDOW.stop - 1}: least overlap "
          f"{overlap:.3e} m, least |F_t|/|F_n| {share:.3f}, largest |F_0 + F_1|/|F| "
          f"{newton:.1e}; from the cut, grain 0 goes from {start_0 * 1e3:+.3f} to "
          f"{end_0 * 1e3:+.3f} mm, grain 1 starts at {start_1 * 1e3:+.3f} mm "
          f"(skin/2 = {half_skin * 1e3:.3f} mm)")
    if not overlap > 0:
        runner.fail(f"sliding pair: contact lost in the window (overlap {overlap:.3e} m)")
    if not (start_0 < 0 < start_1 and end_0 > half_skin):
        runner.fail(f"sliding pair: grain 0 does not cross the cut at x = {cut} m by more than "
                    f"skin/2 from the other side of grain 1 ({start_0}, {start_1}, {end_0} m)")
    if not share > FRICTION_SHARE:
        runner.fail(f"sliding pair: |F_t|/|F_n| falls to {share:.3f}, not above {FRICTION_SHARE}")
    if not newton < NEWTON_TOLERANCE:
        runner.fail(f"sliding pair: |F_0 + F_1| = {newton:.1e} |F|: not the pair's force alone")


def sliding_pair(runner):
    scene = SCENES / "sliding_pair.toml"
    reference = runner.run("pair_n1", scene, 1)
    out = runner.run("pair_n2", scene, 2, "decomposition.dims=[2,1,1]", quiet=False)
    if "grid 2 x 1 x 1 blocks over 2 x " not in runner.banner:
        runner.fail("pair_n2: expected 2 slabs over 2 coarse cells along x; banner:\n" +
                    runner.banner)
    if "snapshots: written on a writer thread while the run steps on" not in runner.banner:
        runner.fail("pair_n2: snapshots are not written on a writer thread; banner:\n" +
                    runner.banner)
    check_sliding_window(runner, scene, reference)
    compare_every_snapshot(runner, "pair_n2", reference, out)
    synchronous = runner.run("pair_n2_synchronous", scene, 2, "decomposition.dims=[2,1,1]",
                             "output.asynchronous=false")
    compare_every_snapshot(runner, "pair_n2_synchronous", out, synchronous)
    if (out / "particles.xmf").read_text() != (synchronous / "particles.xmf").read_text():
        runner.fail("pair_n2_synchronous: particles.xmf differs from the writer thread's")


# ---- killed-checkpoint ------------------------------------------------------------------------

KILL_DT = 3e-5  # s, an explicit step (periodic_gas.toml's automatic one is 3.06e-5 s)
KILL_ROUNDS = (2, 3, 2, 3, 2, 3, 2)  # ranks of each killed round
KILL_DELAY = (0.0, 1.5)  # s after the round's first new checkpoint, uniform
ROUND_LIMIT = 60.0  # s for a round to write its first checkpoint


def read_checkpoint(path):
    """(step, sorted ids) of a checkpoint; raises if the file is missing or damaged."""
    with h5py.File(path, "r") as f:
        step = int(f.attrs["step"])
        ids = np.sort(f["id"][...])
        if np.any(ids[1:] == ids[:-1]):
            raise ValueError("a particle id appears twice")
        for name in ("position_radius", "velocity_inv_mass", "angular_velocity", "force"):
            if f[name].shape[0] != len(ids) or not np.all(np.isfinite(f[name][...])):
                raise ValueError(f"dataset '{name}' does not match 'id'")
    return step, ids


def session_groups(session):
    """Process groups of the live (not zombie) processes of a session."""
    groups = set()
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            stat = pathlib.Path(f"/proc/{entry}/stat").read_text()
        except OSError:
            continue
        state, _, group, sid = stat[stat.rindex(")") + 2:].split()[:4]
        if int(sid) == session and state != "Z":
            groups.add(int(group))
    return groups


def kill_session(process):
    """SIGKILL to every process group of the session `process` leads, until none is left:
    Open MPI gives each rank a process group of its own, so killing mpirun's leaves them
    running."""
    while groups := session_groups(process.pid):
        for group in groups:
            try:
                os.killpg(group, signal.SIGKILL)
            except ProcessLookupError:
                pass
        process.poll()
        time.sleep(0.01)
    process.wait()


class CheckpointWatch:
    """Reads the checkpoint again and again while a round runs; every read must succeed."""

    def __init__(self, runner, path, ids):
        self.runner, self.path, self.ids = runner, path, ids
        self.reads = 0

    def step(self, label):
        try:
            step, ids = read_checkpoint(self.path)
        except FileNotFoundError:
            return 0
        except Exception as error:
            self.runner.fail(f"{label}: checkpoint unreadable while the run goes: {error}")
            return None
        self.reads += 1
        if self.ids is not None and not np.array_equal(ids, self.ids):
            self.runner.fail(f"{label}: checkpoint holds {len(ids)} ids, not the run's particles")
            return None
        return step

    def until_step_above(self, label, process, previous):
        """Reads until a checkpoint after `previous` appears; False if the run ends or stalls."""
        stop = time.monotonic() + ROUND_LIMIT
        while time.monotonic() < stop and process.poll() is None:
            step = self.step(label)
            if step is None:
                return False
            if step > previous:
                return True
            time.sleep(0.015)
        return False

    def until(self, label, moment):
        while time.monotonic() < moment and self.step(label) is not None:
            time.sleep(0.015)


def killed_checkpoint(runner):
    scene = SCENES / "periodic_gas.toml"
    settings = [f"simulation.dt={KILL_DT!r}", f"checkpoint.every={KILL_DT!r}",
                "simulation.end_time=10.0"]
    checkpoint = runner.work / "run" / "checkpoint.h5"
    rng = random.Random(7)
    watch = CheckpointWatch(runner, checkpoint, None)
    step, inside_a_write = 0, 0
    for number, ranks in enumerate(KILL_ROUNDS):
        label = f"round {number} (N = {ranks})"
        command = runner.command("run", scene, ranks, settings, checkpoint if number else None)
        with open(runner.work / f"round_{number}.log", "w") as log:
            process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT,
                                       start_new_session=True)
        wrote = watch.until_step_above(label, process, step)
        if wrote:
            watch.until(label, time.monotonic() + rng.uniform(*KILL_DELAY))
        exited = process.poll()
        kill_session(process)
        if not wrote:
            runner.fail(f"{label}: no new checkpoint (exit {exited}; see round_{number}.log)")
            return
        inside_a_write += checkpoint.with_name("checkpoint.h5.tmp").exists()
        try:
            now, ids = read_checkpoint(checkpoint)
        except Exception as error:
            runner.fail(f"{label}: checkpoint unreadable after SIGKILL: {error}")
            return
        if watch.ids is None:
            watch.ids = ids
        if not now > step or not np.array_equal(ids, watch.ids):
            runner.fail(f"{label}: checkpoint at step {now} after {step}, {len(ids)} ids")
        print(f"{label}: killed at checkpoint step {now}")
        step = now
    print(f"{len(KILL_ROUNDS)} kills, {inside_a_write} inside a write; {watch.reads} reads "
          "while running")
    end = f"simulation.end_time={(step + 3) * KILL_DT!r}"
    runner.run("run", scene, 2, *settings, end, restart=checkpoint)
    final, _ = read_checkpoint(checkpoint)
    if final != step + 3 or checkpoint.with_name("checkpoint.h5.tmp").exists():
        runner.fail(f"last restart: checkpoint at step {final}, not {step + 3}, or a .tmp left")


# ---- tool ---------------------------------------------------------------------------------------

TOOL_COLUMNS = tuple(f"sweep_{c}" for c in ("fx", "fy", "fz", "tx", "ty", "tz"))
TOOL_TOLERANCE = 1e-9  # of the largest value of a column over the run
TOOL_LEAST_DRAFT = 0.5  # N: the sweep meets grains, not an empty bin


def compare_tool_series(runner, label, reference, candidate):
    a, b = series(reference), series(candidate)
    if len(a) != len(b):
        runner.fail(f"{label}: {len(a)} time-series rows against {len(b)}")
        return
    for key in TOOL_COLUMNS:
        x = np.array([float(row[key]) for row in a])
        y = np.array([float(row[key]) for row in b])
        worst = np.max(np.abs(x - y))
        if not worst <= TOOL_TOLERANCE * np.max(np.abs(x)):
            runner.fail(f"{label}: {key} differs by {worst:.3e} (largest {np.max(np.abs(x)):.3e})")


def without_mesh_springs(checkpoint, copy):
    """A copy of `checkpoint` without its mesh records (as written before they existed)."""
    shutil.copy(checkpoint, copy)
    with h5py.File(copy, "r+") as f:
        for name in ("mesh_owner", "mesh_triangle", "mesh_history"):
            del f[name]


def compare_layouts(runner, label, scene, reference, compare_series_of, layouts, *settings):
    """Runs `scene` (with `settings`) on each (name, ranks, dims) of `layouts` into
    LABEL_NAME: the final state must equal `reference` bit for bit, and the time series as
    compare_series_of(runner, name, reference, out) asks."""
    for name, ranks, dims in layouts:
        out = runner.run(f"{label}_{name}", scene, ranks, f"decomposition.dims={dims}", *settings)
        compare_states(runner, name, reference, out)
        compare_series_of(runner, name, reference, out)


def checkpoint_on_three_ranks(runner, label, scene, time, *settings):
    """Runs `scene` (with `settings`) on 3 ranks to `time` into LABEL_restart, checkpointing
    there; returns the checkpoint's path."""
    out = runner.run(f"{label}_restart", scene, 3, f"simulation.end_time={time}",
                     f"checkpoint.every={time}", *settings)
    return out / "checkpoint.h5"


def continue_on_two_ranks(runner, label, scene, reference, checkpoint, stripped, what):
    """Continues `checkpoint` (of run LABEL_restart) on 2 ranks, which must end equal to
    `reference` bit for bit, and its `stripped` copy (without `what`), which must not: the
    restart test sees `what`."""
    out = runner.run(f"{label}_restart", scene, 2, restart=checkpoint)
    compare_states(runner, f"{label}_restart", reference, out)
    stripped_out = runner.run(f"{label}_stripped", scene, 2, restart=stripped)
    if not snapshot_differences(last_snapshot(reference), last_snapshot(stripped_out)):
        runner.fail(f"{label}_stripped: dropping {what} changes nothing; the restart test "
                    "cannot see it")


def restart_sees(runner, label, scene, reference, time, records_of, strip, what):
    """Checkpoints `scene` at `time` on 3 ranks, which must hold some of `what`
    (records_of(file) counts them), and continues it on 2 ranks as continue_on_two_ranks does,
    with a copy that strip(checkpoint, copy) leaves without them."""
    checkpoint = checkpoint_on_three_ranks(runner, label, scene, time)
    with h5py.File(checkpoint, "r") as f:
        records = records_of(f)
    print(f"{label}_restart: {records} {what} in the checkpoint")
    if records == 0:
        runner.fail(f"{label}_restart: the checkpoint holds no {what}")
    stripped = runner.work / f"{label}_stripped.h5"
    strip(checkpoint, stripped)
    continue_on_two_ranks(runner, label, scene, reference, checkpoint, stripped, what)


def tool(runner):
    scene = SCENES / "tool.toml"
    reference = runner.run("tool_n1", scene, 1)
    draft = max(abs(float(row["sweep_fx"])) for row in series(reference))
    print(f"tool_n1: largest |sweep_fx| {draft:.3f} N")
    if not draft > TOOL_LEAST_DRAFT:
        runner.fail(f"tool_n1: largest |sweep_fx| {draft:.3f} N, not above {TOOL_LEAST_DRAFT} N")
    compare_layouts(runner, "tool", scene, reference, compare_tool_series,
                    (("slabs_n2", 2, "[2,1,1]"), ("slabs_n4", 4, "[4,1,1]"),
                     ("blocks_2x2", 4, "[2,2,1]")))
    restart_sees(runner, "tool", scene, reference, 0.09, lambda f: f["mesh_owner"].shape[0],
                 without_mesh_springs, "mesh contact springs")


# ---- piston -------------------------------------------------------------------------------------

PISTON_COLUMNS = ("piston_displacement", "piston_velocity")


def compare_piston_path(runner, label, reference, candidate):
    a, b = series(reference), series(candidate)
    path_a = [tuple(row[key] for key in PISTON_COLUMNS) for row in a]
    path_b = [tuple(row[key] for key in PISTON_COLUMNS) for row in b]
    if path_a != path_b:
        first = next((k for k, (x, y) in enumerate(zip(path_a, path_b)) if x != y), len(path_a))
        runner.fail(f"{label}: the piston's path differs from row {first}")


def without_wall_motion(checkpoint, copy):
    """A copy of `checkpoint` without the walls' motion (as written before it was kept)."""
    shutil.copy(checkpoint, copy)
    with h5py.File(copy, "r+") as f:
        del f["wall_motion"]


def piston(runner):
    scene = SCENES / "piston.toml"
    reference = runner.run("piston_n1", scene, 1)
    travel = float(series(reference)[-1]["piston_displacement"])
    print(f"piston_n1: the piston came down by {travel:.4f} m")
    if not travel > 0.03:
        runner.fail(f"piston_n1: the piston came down by {travel} m only")
    compare_layouts(runner, "piston", scene, reference, compare_piston_path,
                    (("slabs_z_n2", 2, "[1,1,2]"), ("slabs_z_n3", 3, "[1,1,3]"),
                     ("blocks_2x2", 4, "[2,2,1]")))
    half = ["simulation.end_time=0.06", "checkpoint.every=0.06"]
    out = runner.run("piston_restart", scene, 3, *half)
    checkpoint = out / "checkpoint.h5"
    stripped = runner.work / "without_wall_motion.h5"
    without_wall_motion(checkpoint, stripped)
    continue_on_two_ranks(runner, "piston", scene, reference, checkpoint, stripped,
                          "the walls' motion")
    compare_piston_path(runner, "piston_restart", reference, out)


# ---- sticky -------------------------------------------------------------------------------------


def without_formed_flags(checkpoint, copy):
    """A copy of `checkpoint` whose contacts have all forgotten that they formed (JKR's last
    history value zeroed): those held in tension past touch let go."""
    shutil.copy(checkpoint, copy)
    with h5py.File(copy, "r+") as f:
        for name in ("pair_history", "wall_history"):
            values = f[name][...]
            values[:, -1] = 0
            f[name][...] = values


def sticky(runner):
    scene = SCENES / "sticky.toml"
    reference = runner.run("sticky_n1", scene, 1)
    compare_layouts(runner, "sticky", scene, reference, compare_series,
                    (("slabs_n2", 2, "[2,1,1]"), ("slabs_n3", 3, "[3,1,1]"),
                     ("blocks_2x2", 4, "[2,2,1]")))
    checkpoint = checkpoint_on_three_ranks(runner, "sticky", scene, 0.05)
    with h5py.File(checkpoint, "r") as f:
        formed = int(np.count_nonzero(f["pair_history"][:, -1]))
    print(f"sticky_restart: {formed} formed pair contacts in the checkpoint")
    stripped = runner.work / "without_formed_flags.h5"
    without_formed_flags(checkpoint, stripped)
    continue_on_two_ranks(runner, "sticky", scene, reference, checkpoint, stripped,
                          "the contacts' formed flags")


# ---- bonded -------------------------------------------------------------------------------------


def without_bonds(checkpoint, copy):
    """A copy of `checkpoint` whose bond datasets hold no record (as if every bond had broken):
    the clod continues uncemented."""
    shutil.copy(checkpoint, copy)
    with h5py.File(copy, "r+") as f:
        for name in ("bond_owner", "bond_partner", "bond_values"):
            shape, dtype = f[name].shape, f[name].dtype
            del f[name]
            f.create_dataset(name, shape=(0,) + shape[1:], dtype=dtype)


def bond_counts(out):
    """(bonds at the start, broken bonds at the end) of a run's time series."""
    rows = series(out)
    return int(float(rows[0]["bonds"])), int(float(rows[-1]["broken_bonds"]))


def bond_lines_by_ids(path):
    """The bonds of a snapshot (group /bonds/) sorted by their two ids: ids, normal force and
    strength used."""
    with h5py.File(path, "r") as f:
        ids = f["bonds/ids"][...]
        order = np.lexsort((ids[:, 1], ids[:, 0]))
        return (ids[order], f["bonds/normal_force"][...][order],
                f["bonds/strength_used"][...][order])


def compare_bonded(runner, label, reference, candidate):
    """compare_series, the bond columns of every row, and the last snapshot's bonds bit for
    bit."""
    compare_series(runner, label, reference, candidate)
    for key in ("bonds", "broken_bonds"):
        if [row[key] for row in series(reference)] != [row[key] for row in series(candidate)]:
            runner.fail(f"{label}: column {key} differs")
    a = bond_lines_by_ids(last_snapshot(reference))
    b = bond_lines_by_ids(last_snapshot(candidate))
    if any(x.shape != y.shape or not np.array_equal(x, y) for x, y in zip(a, b)):
        runner.fail(f"{label}: the last snapshot's bonds differ")


def bonded(runner):
    scene = SCENES / "bonded.toml"
    reference = runner.run("bonded_n1", scene, 1)
    made, broken = bond_counts(reference)
    print(f"bonded_n1: {made} bonds made, {broken} broken")
    if not 0 < broken < made:
        runner.fail(f"bonded_n1: {broken} of {made} bonds broke; the case needs some of each")
    compare_layouts(runner, "bonded", scene, reference, compare_bonded,
                    (("slabs_n2", 2, "[2,1,1]"), ("slabs_n3", 3, "[3,1,1]"),
                     ("blocks_2x2", 4, "[2,2,1]")))
    restart_sees(runner, "bonded", scene, reference, 0.03, lambda f: f["bond_owner"].shape[0],
                 without_bonds, "bond records")


# ---- adaptive -----------------------------------------------------------------------------------

ADAPTIVE = ('simulation.dt="adaptive"', "simulation.displacement_fraction=0.01")


def step_column(out):
    return [row["dt"] for row in series(out)]


def compare_step_column(runner, label, reference, candidate):
    if step_column(candidate) != step_column(reference):
        runner.fail(f"adaptive_{label}: the dt column differs")


def adaptive(runner):
    scene = SCENES / "tool.toml"
    reference = runner.run("adaptive_n1", scene, 1, *ADAPTIVE)
    steps = sorted({float(dt) for dt in step_column(reference)})
    print(f"adaptive_n1: steps {steps}")
    if len(steps) < 2:
        runner.fail(f"adaptive_n1: the step never changed ({steps})")
    compare_layouts(runner, "adaptive", scene, reference, compare_step_column,
                    (("slabs_n2", 2, "[2,1,1]"), ("blocks_2x2", 4, "[2,2,1]")), *ADAPTIVE)
    half = ["simulation.end_time=0.09", "checkpoint.every=0.09", *ADAPTIVE]
    out = runner.run("adaptive_restart", scene, 3, *half)
    checkpoint = out / "checkpoint.h5"
    with h5py.File(checkpoint, "r") as f:
        saved = {key: int(f.attrs[key]) for key in ("substeps", "list_build_substep",
                                                      "list_build_substeps")}
    print(f"adaptive_restart: the checkpoint holds {saved}")
    if saved["substeps"] < 2 or saved["list_build_substep"] == 0:
        runner.fail(f"adaptive_restart: the checkpoint is not inside split steps: {saved}")
    runner.run("adaptive_restart", scene, 2, *ADAPTIVE, restart=checkpoint)
    compare_states(runner, "adaptive_restart", reference, out)
    refused = runner.run_raw("adaptive_as_auto", scene, 2, restart=checkpoint)
    if refused.returncode != 2 or "simulation.dt" not in refused.stderr:
        runner.fail(f"adaptive_as_auto: exit {refused.returncode}, expected 2 naming "
                    f"simulation.dt:\n{refused.stderr}")


# ---- bed ----------------------------------------------------------------------------------------

BED_SETTINGS = ("simulation.end_time=0.8", "preparation.kinetic_energy=1e-7",
                "preparation.check_after=0.1", "preparation.remove_above=0.03")


def bed_summary(banner):
    """The 'bed: ... particles kept ...' line of a preparation run, up to its output path."""
    for line in banner.splitlines():
        if line.startswith("bed: "):
            return line.split("; written to")[0]
    return None


def bed(runner):
    scene = SCENES / "settle.toml"
    summaries = {}
    for ranks in (1, 3):
        out = runner.run(f"bed_n{ranks}", scene, ranks, *BED_SETTINGS, quiet=False)
        summaries[ranks] = bed_summary(runner.banner)
        print(f"bed_n{ranks}: {summaries[ranks]}")
    if summaries[1] is None or summaries[1] != summaries[3]:
        runner.fail(f"bed summaries differ: {summaries[1]!r} against {summaries[3]!r}")
    a, b = read_bed(runner.work / "bed_n1" / "bed.h5"), read_bed(runner.work / "bed_n3" / "bed.h5")
    for name in a:
        if a[name].shape != b[name].shape or not np.array_equal(a[name], b[name]):
            runner.fail(f"bed_n3: {name} differs from bed_n1's ({a[name].shape} against "
                        f"{b[name].shape})")
    print(f"bed: {len(a['id'])} particles, {len(a['pair_owner'])} pair springs, "
          f"{len(a['wall_owner'])} wall springs")
    bed_start(runner, runner.work / "bed_n1" / "bed.h5")


def bed_start(runner, bed_file):
    """A scene whose only source is `bed_file`, and one that tops it with a tiled layer: each
    rank reads its part of the bed's rows and springs, and 2 and 3 ranks must end where one rank
    does."""
    scene = SCENES / "bed_start.toml"
    source = f'insert.0.bed="{bed_file}"'
    reference = runner.run("bed_start_n1", scene, 1, source)
    for ranks in (2, 3):
        name = f"bed_start_n{ranks}"
        out = runner.run(name, scene, ranks, source)
        compare_states(runner, name, reference, out)
        compare_series(runner, name, reference, out)
    topped = SCENES / "bed_topped.toml"
    reference = runner.run("bed_topped_n1", topped, 1, source)
    out = runner.run("bed_topped_n3", topped, 3, source)
    compare_states(runner, "bed_topped_n3", reference, out)
    compare_series(runner, "bed_topped_n3", reference, out)


def read_bed(path):
    """A bed file's particles in id order and its spring records in (owner, partner or wall)
    order."""
    with h5py.File(path, "r") as f:
        ids = f["id"][...]
        order = np.argsort(ids)
        bed = {name: f[name][...][order] for name in
               ("id", "position_radius", "velocity_inv_mass", "angular_velocity")}
        for kind, key in (("pair", "pair_partner"), ("wall", "wall_index")):
            owner, other = f[f"{kind}_owner"][...], f[key][...]
            order = np.lexsort((other, owner))
            bed[f"{kind}_owner"], bed[key] = owner[order], other[order]
            bed[f"{kind}_history"] = f[f"{kind}_history"][...][order]
        return bed

# ---- cuda ---------------------------------------------------------------------------------------

SKIPPED = 77  # ctest's SKIP_RETURN_CODE


def cuda_unavailable(runner, scene):
    """Why the CUDA backend cannot run here, or None when it can."""
    command = runner.command("cuda_probe", scene, 1, ["simulation.end_time=1e-6"],
                             backend="cuda")
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode == 0:
        return None
    message = result.stdout + result.stderr
    for reason in ("no CUDA device is visible", "this build has no CUDA backend"):
        if reason in message:
            return reason
    sys.exit(f"cuda_probe: exit {result.returncode}\n{message}")


def final_row(out):
    return series(out)[-1]


def cuda(runner):
    scene = SCENES / "settle.toml"
    reason = cuda_unavailable(runner, scene)
    if reason:
        print(f"skipped: {reason}")
        return SKIPPED
    host = runner.run("host_n1", scene, 1)
    device = runner.run("cuda_n1", scene, 1, backend="cuda")
    for name, ranks, dims in (("cuda_slabs_n2", 2, "[2,1,1]"), ("cuda_blocks_2x2", 4, "[2,2,1]")):
        out = runner.run(name, scene, ranks, f"decomposition.dims={dims}", backend="cuda")
        compare_states(runner, name, device, out)
    leaking = SCENES / "leaking_gas.toml"
    leaking_n1 = runner.run("cuda_leaking_n1", leaking, 1, backend="cuda")
    out = runner.run("cuda_leaking_slabs_n2", leaking, 2, "decomposition.dims=[2,1,1]",
                     backend="cuda")
    compare_states(runner, "cuda_leaking_slabs_n2", leaking_n1, out)
    compare_series(runner, "cuda_leaking_slabs_n2", leaking_n1, out)
    start = float(series(host)[0]["potential_gravity"])
    h, d = final_row(host), final_row(device)
    fall = start - float(h["potential_gravity"])
    gap = abs(float(h["potential_gravity"]) - float(d["potential_gravity"]))
    print(f"cuda_n1 against host_n1: potential energy {gap:.3e} J apart of a {fall:.3e} J fall; "
          f"contacts {d['contacts']} against {h['contacts']}")
    if not gap < 0.01 * fall:
        runner.fail(f"cuda_n1: potential energy {gap:.3e} J from the host's ({fall:.3e} J fall)")
    if not abs(int(d["contacts"]) - int(h["contacts"])) <= 0.05 * int(h["contacts"]):
        runner.fail(f"cuda_n1: {d['contacts']} contacts against the host's {h['contacts']}")
    return 0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--binary", required=True)
    parser.add_argument("--mpirun", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("case", choices=["same-physics", "restart", "balance", "momentum",
                                         "leaving", "tiled", "sliding-pair", "killed-checkpoint",
                                         "tool", "piston", "sticky", "bonded", "adaptive", "bed",
                                         "cuda"])
    args = parser.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    runner = Runner(args.binary, args.mpirun, args.work)
    cases = {"same-physics": same_physics, "restart": restart, "balance": balance,
             "momentum": momentum, "leaving": leaving, "tiled": tiled,
             "sliding-pair": sliding_pair,
             "killed-checkpoint": killed_checkpoint, "tool": tool, "piston": piston,
             "sticky": sticky, "bonded": bonded, "adaptive": adaptive, "bed": bed, "cuda": cuda}
    if cases[args.case](runner) == SKIPPED:
        return SKIPPED
    for line in runner.failures:
        print(line)
    return 1 if runner.failures else 0


if __name__ == "__main__":
    sys.exit(main())
