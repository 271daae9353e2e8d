#!/usr/bin/python3
"""Runs one scene over a grid of solver settings (the time step's dt_fraction, the precision
policy, the neighbour skin, the integrator, for the settling bed a particle-size scale, and the
kind of step, "auto" or "adaptive"),
measures each setting's wall time, particle-steps per second and the error of the scene's
observables against a reference run, plots the Pareto front of error against speed and picks
the cheapest setting within each tolerance.

Usage: scripts/speed_vs_error.py SCENE_TYPE [--scene TOML] [--bed BED_H5 ...] [--out DIR]
       [--dt-fraction F ...] [--precision P ...] [--skin M|auto ...] [--integrator I ...]
       [--scale S ...] [--step auto|adaptive ...] [--full] [--repeat N] [--tolerance T ...]
       [--rank-by wall|rate]
       [--set KEY=VALUE]... [--np N] [--solver PATH]

SCENE_TYPE, its scene (--scene overrides it) and the observables each run yields:
- impact (inputs/accuracy/impact.toml): a layer of spheres hits a floor once, without gravity.
  From the first and last snapshot (spheres matched by id; the floor is the plane z = 0):
  restitution, the mean of rebound over approach speed; contact_duration_s, the mean of
  t_leave − t_touch, with t_touch = (z0 − r) / |v0| and t_leave = t_end − (z_end − r) / v_end
  (both from the free flight on either side of the impact).
- settling (inputs/accuracy/settling.toml): a bed poured into a box periodic along x and y.
  From the last snapshot (d the mean diameter): bed_height_m, the mean over columns 2 d square
  of the highest particle top z + r; packing_fraction, the volume of the spheres whose centres
  lie from 2 d above the floor to 2 d below the bed height over that slab's volume; from the
  last time-series row, coordination_number = 2 contacts / particles (the contacts column
  counts particle-particle and particle-wall contacts).
- tillage (inputs/tillage/quickstart_till.toml from --bed, default
  out/tillage-quickstart/bed/bed.h5, which scripts/demo.sh makes): draft_mean_N and
  draft_std_N over the sweep's steady window (scripts/tool_travel.py, as scripts/plot_draft.py
  computes them); each run ends at the window's end.
- silo (inputs/accuracy/silo_discharge.toml from --bed, default out/accuracy/silo-fill/bed.h5,
  which `gpudem-mpi inputs/accuracy/silo_fill.toml` makes): discharge_rate_per_s, grains per
  second, the least-squares slope of `removed` from 0.1 s to the end (scripts/beverloo_fit.py).

Several beds (tillage and silo: --bed with more than one file, e.g. the same bed recipe
poured with other simulation.seed values): every grid point runs on every bed, and each
observable of a point is the mean over the beds of its median over the repeats; a point's
error is that of its mean against the reference's mean. The beds average out what one bed's
packing adds to an observable (the tillage draft and the silo's rate move by several per cent
between runs that differ only in their last digits), and the table gives, per observable, the
standard error of that error: the spread over the beds of the paired difference x_b − x_ref,b
over √(beds), relative to |x_ref|, which pareto.png draws as bars. The grid is checked on the
first bed.

The grid: each axis option lists its values (defaults per scene type, printed at the start).
Its centre is the scene's own setting on each axis (dt_fraction 0.1 unless the scene gives
one, its precision and integrator, its skin or "auto", scale 1, its step "auto" or
"adaptive", "auto" when it gives a number). By default one factor at a
time: the centre and each value of each axis with the other axes at the centre; --full: every
combination. The reference is the centre at the smallest dt_fraction of the grid, in double
precision, at scale 1, with step "auto"; it is always run. Scale S (settling only) turns every box source
[[insert]] with a count into count / S³ spheres (rounded) of radius × S: the same solid volume
in coarser grains. Every run is the scene with --set simulation.dt = the point's step, its
dt_fraction, precision, integrator, neighbor.skin (left to the scene when "auto" is the
scene's), output.every = 0 (the first and last snapshot only) and each --set.

Before any run each grid point is checked with `gpudem-mpi --check` (which also gives its step
and step count). Bad input (an unknown scene type, an axis without values, a value out of
range, --scale on another scene type, a --set key the study sets itself, a missing scene, bed
or solver, a grid point the solver refuses) exits 2 naming the option, before any run; a
failed run exits 1.

Timing: the solver's time loop, from its last line "done: N steps in X s", or, for a run short
enough to print a single progress line (under 2 s), from that line's steps/s (4 digits
against X's 0.01 s); particle-steps/s = the mean of the time series' particle count × N / the
wall time. With step "adaptive", N is the steps the base steps were split into ("done: B steps
(base steps, split into N) in X s"), and the table's dt_s is the base step. --repeat N runs each point N times, interleaved (every point once, then again), so
that the machine's slow spells spread over the grid; the table gives the median, least and
largest wall time and the median of each observable.

Errors: |x − x_ref| / |x_ref| for each observable x (|x − x_ref| where x_ref = 0), and
max_error, the largest. For each --tolerance (default 0.01 0.05) the recommended setting is
the cheapest row whose every error is within it: the least median wall time, or with
--rank-by rate the most particle-steps/s. The reference always qualifies.

Output in OUT (default out/speed-vs-error/SCENE_TYPE): runs/POINT-rK (repeat K; POINT-bJ-rK
on bed J, from 1, with several beds) with the
solver's output, solver.log, run.json (its command line, written first) and result.json
(wall time, steps, particles and observables, written last: the mark of a finished run);
table.csv (one row per grid point with a finished run, rewritten after each run),
pareto.png and recommendation.json. The study resumes: a run with result.json is not run
again, and a run folder without one (a killed run) is emptied and run again from its start,
so each wall time is of one whole run. A run folder whose run.json holds another command line
is refused. A progress line "[done/total] ... ETA" follows each run. One rank runs the solver
directly, more through mpirun; unless OMP_NUM_THREADS is set each rank gets an equal share of
the cores (as scripts/tillage_study.py).
"""
import argparse
import csv
import dataclasses
import itertools
import json
import math
import os
import pathlib
import re
import shutil
import statistics
import subprocess
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import beverloo_fit  # noqa: E402
import plot_draft  # noqa: E402
import repose_angle  # noqa: E402
from tillage_study import (GEOMETRY_KEYS, StudyError, bed_insert_index,  # noqa: E402
                           check_earlier_runs, launch)
from tool_travel import SceneError, find_tool, load_scene, steady_window  # noqa: E402

PROJECT = pathlib.Path(__file__).resolve().parent.parent
AXES = ("dt_fraction", "precision", "skin", "integrator", "scale", "step")
OPTIONS = {axis: "--" + axis.replace("_", "-") for axis in AXES}
PRECISIONS = ("double", "mixed", "float")
INTEGRATORS = ("velocity_verlet", "symplectic_euler")
STEPS = ("auto", "adaptive")
SILO_WINDOW_START = 0.1  # s: the discharge rate is fitted from here to the end
STUDY_KEYS = re.compile(r"simulation\.(dt|dt_fraction|precision|integrator)|neighbor\.skin|"
                        r"output\.every")
BED_KEY = re.compile(r"insert\.\d+\.bed")  # tillage and silo: --bed
SCALE_KEYS = re.compile(r"insert\.\d+\.(count|radius.*)")  # settling: --scale


class MeasureError(Exception):
    """A finished run whose output does not give the observables (exit 1)."""


@dataclasses.dataclass(frozen=True)
class SceneType:
    scene: str
    observables: tuple
    dt_fractions: tuple
    skins: tuple
    bed: str = None  # the default --bed of a scene that starts from a prepared bed
    scales: tuple = ()  # empty: the scene type takes no --scale


SCENE_TYPES = {
    "impact": SceneType("inputs/accuracy/impact.toml", ("restitution", "contact_duration_s"),
                        (0.01, 0.02, 0.05, 0.1, 0.2, 0.5), ("auto", "0.0005", "0.002")),
    "settling": SceneType("inputs/accuracy/settling.toml",
                          ("packing_fraction", "bed_height_m", "coordination_number"),
                          (0.025, 0.05, 0.1, 0.2, 0.4), ("auto", "0.0004", "0.0016"),
                          scales=(1, 1.5, 2)),
    "tillage": SceneType("inputs/tillage/quickstart_till.toml", ("draft_mean_N", "draft_std_N"),
                         (0.03, 0.05, 0.1, 0.2, 0.4), ("auto", "0.002", "0.007"),
                         bed="out/tillage-quickstart/bed/bed.h5"),
    "silo": SceneType("inputs/accuracy/silo_discharge.toml", ("discharge_rate_per_s",),
                      (0.025, 0.05, 0.1, 0.2, 0.4), ("auto", "0.0005", "0.002"),
                      bed="out/accuracy/silo-fill/bed.h5"),
}


@dataclasses.dataclass(frozen=True)
class Point:
    """One setting of the grid."""
    dt_fraction: float
    precision: str
    skin: str  # "auto" or metres as given
    integrator: str
    scale: float
    step: str = "auto"

    @property
    def name(self):
        name = (f"dt{self.dt_fraction:g}-{self.precision}-skin{self.skin}-{self.integrator}"
                f"-scale{self.scale:g}" + ("-adaptive" if self.step == "adaptive" else ""))
        return re.sub(r"[^\w.+=-]", "_", name)


@dataclasses.dataclass
class Run:
    """Repeat `repeat` of `point` on bed number `bed` (1 without beds); `name` is its folder
    under OUT/runs."""
    point: Point
    repeat: int
    name: str
    solver_args: list
    bed: int = 1


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add = parser.add_argument
    add("scene_type", choices=sorted(SCENE_TYPES), metavar="SCENE_TYPE",
        help="one of " + ", ".join(sorted(SCENE_TYPES)))
    add("--scene", metavar="TOML", help="default: the scene type's")
    add("--bed", nargs="+", metavar="BED_H5", help="tillage and silo: the prepared bed(s)")
    add("--out", metavar="DIR", help="default out/speed-vs-error/SCENE_TYPE")
    add("--dt-fraction", nargs="+", type=float, metavar="F")
    add("--precision", nargs="+", metavar="P")
    add("--skin", nargs="+", metavar="M|auto")
    add("--integrator", nargs="+", metavar="I")
    add("--scale", nargs="+", type=float, metavar="S", help="settling: particle-size scale")
    add("--step", nargs="+", choices=STEPS, metavar="auto|adaptive")
    add("--full", action="store_true", help="every combination, not one factor at a time")
    add("--repeat", type=int, default=1, metavar="N")
    add("--tolerance", nargs="+", type=float, default=[0.01, 0.05], metavar="T")
    add("--rank-by", choices=("wall", "rate"), default="wall")
    add("--set", action="append", default=[], metavar="KEY=VALUE", help="for every run")
    add("--np", type=int, default=1, help="MPI ranks per run")
    add("--solver", default=str(PROJECT / "build/gpudem-mpi"), metavar="PATH")
    return parser.parse_args()


def fill_defaults(args, scene_type):
    """The scene type's defaults for what the options leave out."""
    args.scene = args.scene or str(PROJECT / scene_type.scene)
    if scene_type.bed and not args.bed:
        args.bed = [str(PROJECT / scene_type.bed)]
    args.out = args.out or str(PROJECT / "out/speed-vs-error" / args.scene_type)
    args.dt_fraction = args.dt_fraction or list(scene_type.dt_fractions)
    args.precision = args.precision or list(PRECISIONS)
    args.skin = args.skin or list(scene_type.skins)
    args.integrator = args.integrator or list(INTEGRATORS)
    args.scale = args.scale or list(scene_type.scales or (1,))
    args.step = args.step or list(STEPS)


def check_axes(args, scene_type):
    """Refuses what the study itself cannot take; the solver checks each grid point's values."""
    if any(s <= 0 for s in args.scale):
        raise StudyError("--scale takes values > 0")
    if not scene_type.scales and args.scale != [1]:
        raise StudyError(f"--scale: the {args.scene_type} scene keeps its particles "
                         "(only settling scales its bed)")
    if args.repeat < 1 or args.np < 1:
        raise StudyError("--repeat and --np take values >= 1")
    if any(t <= 0 for t in args.tolerance):
        raise StudyError("--tolerance takes values > 0")


def check_files_and_sets(args, scene_type):
    files = [(args.scene, "--scene"), (args.solver, "--solver")]
    beds = [(bed, "--bed") for bed in args.bed] if scene_type.bed else []
    for path, option in files + beds:
        if not pathlib.Path(path).is_file():
            raise StudyError(f"{option}: no file {path}")
    if not os.access(args.solver, os.X_OK):
        raise StudyError(f"--solver: {args.solver} is not executable")
    if args.bed and not scene_type.bed:
        raise StudyError(f"--bed: the {args.scene_type} scene starts without a bed")
    if args.bed and len(set(map(os.path.realpath, args.bed))) < len(args.bed):
        raise StudyError("--bed: a bed given twice")
    if args.np > 1 and not shutil.which("mpirun"):
        raise StudyError("--np: more than one rank needs mpirun, which is not on the PATH")
    for setting in args.set:
        key = setting.partition("=")[0]
        if "=" not in setting:
            raise StudyError(f"--set {setting}: expected KEY=VALUE")
        if STUDY_KEYS.fullmatch(key) or (scene_type.bed and BED_KEY.fullmatch(key)) or (
                scene_type.scales and SCALE_KEYS.fullmatch(key)):
            raise StudyError(f"--set {key}: the study sets this key itself (use the grid "
                             "options or --bed)")
        if args.scene_type == "tillage" and (GEOMETRY_KEYS.fullmatch(key) or
                                             key == "simulation.end_time"):
            raise StudyError(f"--set {key}: the study times the sweep's steady window from "
                             "the scene file; change this key there")

def centre(scene):
    """The scene's own setting on each axis."""
    simulation = scene.get("simulation", {})
    skin = scene.get("neighbor", {}).get("skin", "auto")
    step = "adaptive" if simulation.get("dt") == "adaptive" else "auto"
    return Point(float(simulation.get("dt_fraction", 0.1)),
                 simulation.get("precision", "double"), str(skin),
                 simulation.get("integrator", "velocity_verlet"), 1.0, step)


def grid(args, middle):
    """The reference first, then the grid points (one factor at a time, or --full)."""
    values = {axis: getattr(args, axis) for axis in AXES}
    if args.full:
        points = [Point(*combination) for combination in itertools.product(
            *(values[axis] for axis in AXES))]
    else:
        points = [middle] + [dataclasses.replace(middle, **{axis: value})
                             for axis in AXES for value in values[axis]]
    reference = dataclasses.replace(middle, dt_fraction=min(values["dt_fraction"] +
                                                               [middle.dt_fraction]),
                                    precision="double", scale=1.0, step="auto")
    unique = {}
    for point in [reference] + points:
        unique.setdefault(point.name, point)
    return reference, list(unique.values())


def options_of(point, middle):
    """The options that move `point` off the centre, as a user wrote them."""
    moved = [f"{OPTIONS[axis]} {getattr(point, axis):g}" if axis in ("dt_fraction", "scale")
             else f"{OPTIONS[axis]} {getattr(point, axis)}"
             for axis in AXES if getattr(point, axis) != getattr(middle, axis)]
    return ", ".join(moved) or "--scene/--set (the grid's centre)"


def scale_settings(scene, scale):
    """--set values that make every box source with a count `scale` times coarser."""
    if scale == 1:
        return []
    settings = []
    for index, source in enumerate(scene.get("insert", [])):
        if "region" not in source or "count" not in source:
            continue
        settings.append(f"insert.{index}.count={max(1, round(source['count'] / scale**3))}")
        radius = source["radius"]
        if not isinstance(radius, dict):
            settings.append(f"insert.{index}.radius={radius * scale!r}")
            continue
        for key in ("mean", "spread", "stddev", "min", "max"):
            if key in radius:
                settings.append(f"insert.{index}.radius.{key}={radius[key] * scale!r}")
        if "values" in radius:
            values = ", ".join(repr(v * scale) for v in radius["values"])
            settings.append(f"insert.{index}.radius.values=[{values}]")
    return settings


def scene_context(args, scene):
    """What the scene type needs beyond the grid: {'settings': [...], 'tool', 'window'}."""
    context = {"settings": [], "scene": scene, "bed_insert": None}
    if args.scene_type in ("tillage", "silo"):
        context["bed_insert"] = bed_insert_index(scene, args.scene)
    if args.scene_type == "tillage":
        try:
            tool = find_tool(scene, args.scene, "sweep")
            end = scene.get("simulation", {}).get("end_time")
            window = steady_window(tool, scene, end)
        except SceneError as error:
            raise StudyError(f"--scene: {error}") from None
        context.update(tool=tool, window=window)
        context["settings"].append(f"simulation.end_time={window[1]!r}")
    return context


def solver_args(args, context, point, out_dir, bed=None):
    """The command-line arguments (after the executable) of a run of `point` on `bed`."""
    beds = [] if bed is None else \
        [f'insert.{context["bed_insert"]}.bed="{pathlib.Path(bed).resolve()}"']
    settings = [*beds, *context["settings"], f'simulation.dt="{point.step}"',
                f"simulation.dt_fraction={point.dt_fraction!r}",
                f'simulation.precision="{point.precision}"',
                f'simulation.integrator="{point.integrator}"',
                'neighbor.skin="auto"' if point.skin == "auto" else f"neighbor.skin={point.skin}",
                "output.every=0", *scale_settings(context["scene"], point.scale), *args.set]
    command = [str(pathlib.Path(args.scene).resolve()), "--output-dir", str(out_dir)]
    return command + [word for s in settings for word in ("--set", s)]


def check_point(args, context, point, middle):
    """Runs gpudem-mpi --check on `point`: {'dt_s', 'steps', 'particles'}; refuses a point
    the solver refuses, naming its options."""
    words = solver_args(args, context, point, pathlib.Path(args.out, "check"),
                        args.bed[0] if args.bed else None)
    env = dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "1"))
    result = subprocess.run([args.solver, *words, "--check"], capture_output=True, text=True,
                            env=env)
    text = result.stdout + result.stderr
    if result.returncode != 0:
        last = (text.strip().splitlines() or ["(no output)"])[-1]
        raise StudyError(f"{options_of(point, middle)}: gpudem-mpi --check refuses grid point "
                         f"{point.name}: {last}")
    timing = re.search(r"^dt = (\S+) s .*?, (\d+) steps to t", text, re.M)
    particles = re.search(r": (\d+) particles", text)
    if not timing or not particles:
        raise StudyError(f"--solver: cannot read the step and particle count from "
                         f"{args.solver} --check:\n{text}")
    return {"dt_s": float(timing[1]), "steps": int(timing[2]), "particles": int(particles[1])}


def plan(args):
    """The checked inputs: (scene type's context, centre, reference, points, checks, runs)."""
    scene_type = SCENE_TYPES[args.scene_type]
    fill_defaults(args, scene_type)
    check_axes(args, scene_type)
    check_files_and_sets(args, scene_type)
    try:
        scene = load_scene(args.scene)
    except SceneError as error:
        raise StudyError(f"--scene: {error}") from None
    context = scene_context(args, scene)
    middle = centre(scene)
    reference, points = grid(args, middle)
    checks = {point.name: check_point(args, context, point, middle) for point in points}
    runs = []
    beds = list(enumerate(args.bed or [None], 1))
    for repeat, (number, bed), point in itertools.product(range(1, args.repeat + 1), beds, points):
        name = f"{point.name}-b{number}-r{repeat}" if len(beds) > 1 else f"{point.name}-r{repeat}"
        out_dir = pathlib.Path(args.out, "runs", name).resolve()
        runs.append(Run(point, repeat, name, solver_args(args, context, point, out_dir, bed),
                        number))
    check_earlier_runs(runs, args.out)
    return context, middle, reference, points, checks, runs


def solver_timing(log):
    """(steps, wall seconds) of the time loop, from the solver's output `log`."""
    done = re.search(r"^done: (\d+) steps(?: \(base steps, split into (\d+)\))? in ([\d.]+) s",
                     log, re.M)
    if not done:
        raise MeasureError("the solver's output has no line 'done: N steps in X s'")
    base_steps, seconds = int(done[1]), float(done[3])
    steps = int(done[2]) if done[2] else base_steps
    lines = re.findall(r"^t = \S+ s  step (\d+)/(\d+)  (\S+) steps/s", log, re.M)
    if len(lines) == 1 and lines[0][0] == lines[0][1] and float(lines[0][2]) > 0:
        seconds = base_steps / float(lines[0][2])  # one line: the whole run's rate, 4 digits
    return steps, max(seconds, 0.005)  # "0.00 s": below the line's resolution


def read_timeseries(run_dir):
    with open(run_dir / "timeseries.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise MeasureError(f"{run_dir / 'timeseries.csv'} has no row")
    return rows


def snapshot(path, fields):
    """The datasets `fields` of a snapshot, in the order of the particles' ids, and its time."""
    with h5py.File(path, "r") as f:
        order = np.argsort(f["id"][:])
        return [f[name][:][order] for name in fields], float(f.attrs["time"])


def measure_impact(run_dir, context):
    files = sorted(run_dir.glob("particles_*.h5"))
    if len(files) < 2:
        raise MeasureError(f"{run_dir}: fewer than two snapshots")
    (x0, v0, r), _ = snapshot(files[0], ("position", "velocity", "radius"))
    (x1, v1), end = snapshot(files[-1], ("position", "velocity"))
    approach, rebound = -v0[:, 2], v1[:, 2]
    if (approach <= 0).any() or (rebound <= 0).any():
        raise MeasureError(f"{run_dir}: a sphere does not move to the floor at the start or "
                           "away from it at the end")
    touch = (x0[:, 2] - r) / approach
    leave = end - (x1[:, 2] - r) / rebound
    return {"restitution": float(np.mean(rebound / approach)),
            "contact_duration_s": float(np.mean(leave - touch))}


def bed_height(positions, radii, width, low, high):
    """The mean over columns `width` square (the box low..high in x and y) of the highest
    particle top."""
    cells = np.maximum(1, np.floor((np.asarray(high) - low) / width)).astype(int)
    column = np.floor((positions[:, :2] - low) / (np.asarray(high) - low) * cells).astype(int)
    column = np.clip(column, 0, cells - 1)
    keys = column[:, 0] * cells[1] + column[:, 1]
    tops = positions[:, 2] + radii
    return float(np.mean([tops[keys == key].max() for key in np.unique(keys)]))


def measure_settling(run_dir, context):
    files = sorted(run_dir.glob("particles_*.h5"))
    positions, radii = repose_angle.read_hdf5(files[-1])
    domain = context["scene"]["domain"]
    low, high = np.array(domain["min"][:2]), np.array(domain["max"][:2])
    d = 2 * radii.mean()
    height = bed_height(positions, radii, 2 * d, low, high)
    floor = domain["min"][2]
    slab = (positions[:, 2] >= floor + 2 * d) & (positions[:, 2] <= height - 2 * d)
    if not slab.any():
        raise MeasureError(f"{run_dir}: the bed is too shallow for a slab 2 d from its faces")
    solid = (4 / 3 * math.pi * radii[slab] ** 3).sum()
    last = read_timeseries(run_dir)[-1]
    return {"packing_fraction": float(solid / (np.prod(high - low) * (height - 4 * d - floor))),
            "bed_height_m": height,
            "coordination_number": 2 * float(last["contacts"]) / float(last["particles"])}


def measure_tillage(run_dir, context):
    tool, (start, end) = context["tool"], context["window"]
    rows = plot_draft.read_rows(run_dir / "timeseries.csv", tool.name)
    time_s, forces = plot_draft.components(rows, tool.name, tool.travel, tool.up)
    steady = [f for t, f in zip(time_s, forces["draft"]) if start <= t <= end]
    if not steady:
        raise MeasureError(f"{run_dir}: no time-series row in the window {start}..{end} s")
    mean, std = plot_draft.mean_std(steady)
    return {"draft_mean_N": mean, "draft_std_N": std}


def measure_silo(run_dir, context):
    try:
        rate = beverloo_fit.discharge_rate(run_dir, (SILO_WINDOW_START, None), 1.0)[0]
    except KeyError as error:
        raise MeasureError(str(error)) from None
    return {"discharge_rate_per_s": float(rate)}


MEASURES = {"impact": measure_impact, "settling": measure_settling, "tillage": measure_tillage,
            "silo": measure_silo}


def run_once(args, run, context):
    """The result of `run`, running it first unless an earlier study finished it;
    (result, whether it ran)."""
    run_dir = pathlib.Path(args.out, "runs", run.name)
    if (run_dir / "result.json").is_file():
        return json.loads((run_dir / "result.json").read_text()), False
    shutil.rmtree(run_dir, ignore_errors=True)  # a killed run starts again, to be timed whole
    run_dir.mkdir(parents=True)
    record = run_dir / "run.json.part"
    record.write_text(json.dumps({"solver_args": run.solver_args}, indent=1))
    record.replace(run_dir / "run.json")
    code = launch(args, run, run_dir / "solver.log")
    log = (run_dir / "solver.log").read_text()
    if code != 0:
        tail = "\n".join(log.splitlines()[-5:])
        sys.exit(f"speed_vs_error.py: run {run.name} failed (exit {code}); "
                 f"{run_dir / 'solver.log'} ends:\n{tail}")
    try:
        steps, wall = solver_timing(log)
        particles = statistics.fmean(float(r["particles"]) for r in read_timeseries(run_dir))
        observables = MEASURES[args.scene_type](run_dir, context)
    except (MeasureError, OSError, KeyError, ValueError) as error:
        sys.exit(f"speed_vs_error.py: run {run.name}: cannot measure it: {error}")
    result = {"steps": steps, "wall_s": wall, "particles": particles,
              "particle_steps_per_s": particles * steps / wall, "observables": observables}
    staging = run_dir / "result.json.part"
    staging.write_text(json.dumps(result, indent=1) + "\n")
    staging.replace(run_dir / "result.json")  # the mark of a finished run, written last
    return result, True


def relative_errors(values, reference):
    """|x − x_ref| / |x_ref| for each observable (|x − x_ref| where x_ref = 0)."""
    return {key: abs(values[key] - ref) / (abs(ref) if ref != 0 else 1.0)
            for key, ref in reference.items()}


def point_row(point, by_bed, check):
    """The table row of `point` from its finished runs `by_bed` ({bed: [result of each
    repeat]}), errors left out: each observable the mean over the beds of its median over the
    repeats (per_bed: those medians)."""
    results = [r for runs in by_bed.values() for r in runs]
    walls = [r["wall_s"] for r in results]
    row = {"point": point.name, **{axis: getattr(point, axis) for axis in AXES},
           "dt_s": check["dt_s"], "particles": statistics.median(r["particles"] for r in results),
           "steps": results[0]["steps"], "repeats": min(len(runs) for runs in by_bed.values()),
           "beds": len(by_bed), "wall_s": statistics.median(walls), "wall_s_min": min(walls),
           "wall_s_max": max(walls)}
    row["particle_steps_per_s"] = row["particles"] * row["steps"] / row["wall_s"]
    names = results[0]["observables"]
    row["per_bed"] = {bed: {k: statistics.median(r["observables"][k] for r in runs)
                            for k in names} for bed, runs in by_bed.items()}
    row["observables"] = {k: statistics.fmean(v[k] for v in row["per_bed"].values())
                          for k in names}
    return row


def error_standard_errors(row, reference):
    """Per observable: the standard error of the mean paired difference x_b − x_ref,b over the
    beds both have run, relative to |x_ref| (NaN with fewer than two such beds)."""
    beds = sorted(set(row["per_bed"]) & set(reference["per_bed"]))
    spread = {}
    for key, ref in reference["observables"].items():
        if len(beds) < 2:
            spread[key] = math.nan
            continue
        differences = [row["per_bed"][b][key] - reference["per_bed"][b][key] for b in beds]
        spread[key] = statistics.stdev(differences) / math.sqrt(len(beds)) / \
            (abs(ref) if ref != 0 else 1.0)
    return spread


def table_rows(points, reference, results, checks):
    """One row per point with a finished run; errors against the reference once it has run."""
    rows = []
    for point in points:
        by_bed = {}
        for (name, bed, _), result in results.items():
            if name == point.name:
                by_bed.setdefault(bed, []).append(result)
        if by_bed:
            rows.append(point_row(point, by_bed, checks[point.name]))
    ref = next((row for row in rows if row["point"] == reference.name), None)
    for row in rows:
        row["reference"] = row is ref
        errors = relative_errors(row["observables"], ref["observables"]) if ref else {}
        row["errors"] = errors
        row["error_se"] = error_standard_errors(row, ref) if ref else {}
        row["max_error"] = max(errors.values()) if errors else math.nan
    return rows


def recommend(rows, tolerance, rank_by="wall"):
    """The cheapest row whose every error is within `tolerance` (max_error <= tolerance):
    least wall_s, or with rank_by "rate" most particle_steps_per_s; the first of equals;
    None when no row qualifies."""
    within = [row for row in rows if row["max_error"] <= tolerance]
    if not within:
        return None
    if rank_by == "rate":
        return max(within, key=lambda row: row["particle_steps_per_s"])
    return min(within, key=lambda row: row["wall_s"])


def pareto_front(speeds, errors):
    """The indices of the points that no other beats (as fast or faster and as accurate or more,
    better in one), by rising speed."""
    front = []
    for i, (speed, error) in enumerate(zip(speeds, errors)):
        beaten = any(s >= speed and e <= error and (s > speed or e < error)
                     for s, e in zip(speeds, errors))
        if not beaten and not math.isnan(error):
            front.append(i)
    return sorted(front, key=lambda i: (speeds[i], -errors[i]))


def write_table(path, rows, observables):
    columns = ["point", "reference", *AXES, "dt_s", "particles", "steps", "repeats", "beds",
               "wall_s", "wall_s_min", "wall_s_max", "particle_steps_per_s", *observables,
               *(f"{name}_error" for name in observables),
               *(f"{name}_error_se" for name in observables), "max_error"]
    with open(path, "w", newline="") as f:
        table = csv.writer(f)
        table.writerow(columns)
        for row in rows:
            values = {**row, **row["observables"], "reference": int(row["reference"]),
                      **{f"{k}_error": v for k, v in row["errors"].items()},
                      **{f"{k}_error_se": v for k, v in row["error_se"].items()}}
            table.writerow([format_value(values.get(column, "")) for column in columns])


def format_value(value):
    if isinstance(value, float):
        return f"{value:.8g}"
    return str(value)


def short_label(row, middle):
    moved = [f"{axis}={row[axis]:g}" if isinstance(row[axis], float) else f"{axis}={row[axis]}"
             for axis in AXES if row[axis] != getattr(middle, axis)]
    return ", ".join(moved) or "centre"


def largest_error_se(row):
    """The standard error of the row's largest error (NaN with one bed)."""
    worst = max(row["errors"], key=row["errors"].get)
    return row["error_se"].get(worst, math.nan)


def plot_front(path, rows, middle, tolerances):
    """Max error against particle-steps/s and against wall time, the Pareto front marked."""
    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    shown = [row for row in rows if row["max_error"] > 0]
    reference = next(row for row in rows if row["reference"])
    for ax, key, better in ((axes[0], "particle_steps_per_s", 1), (axes[1], "wall_s", -1)):
        speeds = [better * row[key] for row in shown]
        front = pareto_front(speeds, [row["max_error"] for row in shown])
        spread = [0.0 if math.isnan(se) else se for se in map(largest_error_se, shown)]
        low = [min(se, 0.9 * row["max_error"]) for se, row in zip(spread, shown)]  # log axis
        ax.errorbar([row[key] for row in shown], [row["max_error"] for row in shown],
                    yerr=[low, spread], fmt="o", color="C0",
                    label="grid points (bars: standard error over the beds)")
        ax.plot([shown[i][key] for i in front], [shown[i]["max_error"] for i in front], "-s",
                color="C3", label="Pareto front")
        for row in shown:
            ax.annotate(short_label(row, middle), (row[key], row["max_error"]), fontsize=6,
                        xytext=(3, 3), textcoords="offset points")
        ax.axvline(reference[key], color="k", ls=":", label="reference (error 0)")
        for tolerance in tolerances:
            ax.axhline(tolerance, color="grey", ls="--", lw=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.grid(alpha=0.3, which="both")
    axes[0].set_xlabel("particle-steps/s (more is faster)")
    axes[1].set_xlabel("wall time of the run [s] (median over repeats)")
    axes[0].set_ylabel("largest relative error of the observables")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def recommendations(rows, tolerances, rank_by):
    """{tolerance: the recommended row's point, settings, wall time, speed and errors}."""
    picks = {}
    for tolerance in tolerances:
        row = recommend(rows, tolerance, rank_by)
        picks[f"{tolerance:g}"] = None if row is None else {
            key: row[key] for key in ("point", *AXES, "dt_s", "wall_s", "particle_steps_per_s",
                                      "beds", "max_error", "errors", "error_se", "observables")}
    return picks


def report(picks, reference, rank_by):
    cost = "most particle-steps/s" if rank_by == "rate" else "least wall time"
    for tolerance, pick in picks.items():
        if pick is None:
            print(f"within {float(tolerance):.3g}: no grid point")
            continue
        settings = ", ".join(f"{axis} {pick[axis]}" for axis in AXES)
        spread = largest_error_se(pick)
        over = "" if math.isnan(spread) else \
            f" ± {spread * 100:.2g} % (standard error over {pick['beds']} beds)"
        print(f"within {float(tolerance) * 100:g} % ({cost}): {pick['point']} ({settings}): "
              f"{pick['wall_s']:.3g} s, {reference['wall_s'] / pick['wall_s']:.3g} times as fast "
              f"as the reference, largest error {pick['max_error'] * 100:.3g} %{over}")


def progress(done, total, run, result, ran, rows, runs_left, checks, rates):
    """The line printed once a run is done; the ETA from the particle-steps left and the mean
    rate of the runs made so far."""
    row = next((r for r in rows if r["point"] == run.point.name), None)
    error = "" if row is None or math.isnan(row["max_error"]) else \
        f", largest error {row['max_error'] * 100:.3g} %"
    work = sum(checks[r.point.name]["steps"] * checks[r.point.name]["particles"]
               for r in runs_left)
    eta = "all done" if not runs_left else "ETA once a run is timed"
    if runs_left and rates:
        eta = f"ETA {work / statistics.fmean(rates) / 60:.1f} min"
    how = "ran" if ran else "done before"
    return (f"[{done}/{total}] {run.name}: {result['wall_s']:.3g} s, "
            f"{result['particle_steps_per_s']:.3g} particle-steps/s{error} ({how}); {eta}")


def main():
    args = parse_args()
    try:
        context, middle, reference, points, checks, runs = plan(args)
    except StudyError as error:
        print(f"speed_vs_error.py: {error}", file=sys.stderr)
        return 2
    print(f"speed against error, {args.scene_type}: {len(points)} grid points x {args.repeat} "
          f"= {len(runs)} runs in {args.out}; reference {reference.name}", flush=True)
    out = pathlib.Path(args.out)
    results, rates, rows = {}, [], []
    for done, run in enumerate(runs, 1):
        result, ran = run_once(args, run, context)
        results[(run.point.name, run.bed, run.repeat)] = result
        if ran:
            rates.append(result["particle_steps_per_s"])
        rows = table_rows(points, reference, results, checks)
        write_table(out / "table.csv", rows, SCENE_TYPES[args.scene_type].observables)
        print(progress(done, len(runs), run, result, ran, rows, runs[done:], checks, rates),
              flush=True)
    plot_front(out / "pareto.png", rows, middle, args.tolerance)
    picks = recommendations(rows, args.tolerance, args.rank_by)
    (out / "recommendation.json").write_text(json.dumps(
        {"scene_type": args.scene_type, "rank_by": args.rank_by, "reference": reference.name,
         "recommended": picks}, indent=1) + "\n")
    report(picks, next(row for row in rows if row["reference"]), args.rank_by)
    print(f"table: {out / 'table.csv'}; plot: {out / 'pareto.png'}; "
          f"recommendation: {out / 'recommendation.json'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
