#!/usr/bin/python3
"""Calibrates scene keys of gpudem-mpi (any key --set takes) to measured targets of a run: the
draft on a tillage tool (its mean and standard deviation over the steady window) and the height
of the bed, each with its measured uncertainty. One gpudem-mpi run per evaluation.

Usage: scripts/calibrate.py SPEC [--out DIR] [--optimizer bo|de] [--evaluations N] [--seed S]
       [--population NP] [--mutation F] [--crossover CR] [--batch B] [--initial N]
       [--jobs J] [--np N] [--solver PATH] [--slurm [--sbatch-args TEXT] [--poll S]]
       [--check | --sensitivity [--run-sd QUANTITY=SD]...]

SPEC is a TOML file (docs/input.md, "Calibration: scripts/calibrate.py"): a [calibration]
table (the pass scene, the bed or the scene that makes it, the tool, the window, settings for
every run), one [[parameter]] per calibrated value (its key or keys, min, max, log, whether it
changes the bed) and one [[target]] per measured quantity (draft_mean, draft_std, bed_height:
value and sigma). The objective is Σ ((simulated − value) / sigma)² over the targets.

The optimizers work on the unit cube of the parameters (linear, or logarithmic with log = true):
--optimizer bo, Gaussian-process Bayesian optimization (default: --evaluations 100, batches of
--batch 4 proposals after a Latin-hypercube start of --initial 2d + 2 points), or
--optimizer de, differential evolution rand/1/bin (default: --population 60, --mutation 0.8,
--crossover 0.5, --evaluations 2700, a generation at a time); both from --seed (default 1)
(scripts/calibration_optimizers.py). Each batch's runs go --jobs at a time, each on --np MPI
ranks and, unless OMP_NUM_THREADS is set, its share of the cores; with --slurm each batch is a
Slurm job array (its script in OUT/slurm/, submitted with sbatch and --sbatch-args, its run
folders polled every --poll s for their exit codes).

An evaluation runs the bed scene first when a parameter changes the bed (bed = true; one bed
per distinct set of those values, in OUT/beds/, reused by every evaluation with the same
values), then the pass from that bed in OUT/runs/eNNNNN, and appends one line to
OUT/evaluations.jsonl (flushed and synced to disk): the point, the parameter values, the
targets, the objective, the wall time and the solver's version and commit. The optimizers are
deterministic given the seed and the objective values, and an evaluation already in that file
is not run again: the same command continues a calibration that was stopped at any moment, and
a larger --evaluations extends it. A file made with another spec or other optimizer settings
is refused. Each evaluation prints "[done/total] ... best ... ETA"; OUT/convergence.png,
OUT/parameters.png, OUT/best_draft.png (the best run's draft beside the measured band) and
OUT/best.json are rewritten as it goes.

--check validates the spec and the options (gpudem-mpi --check on the scenes with every
parameter at its bounds) and exits. --sensitivity reads OUT/evaluations.jsonl, fits each
target with a Gaussian process through the evaluations that ran through, prints each target's
slope along each parameter at the best (with its standard deviation) and whether the optimum is
unique or a ridge (the objective's Gauss–Newton Hessian; scripts/calibration_sensitivity.py),
writes OUT/sensitivity.json, and runs nothing. --run-sd QUANTITY=SD gives a target's spread
between runs that differ only in chance (bed realisations): the fit takes at least that much
noise, and does not read the scatter of nearby evaluations that share one bed seed as the
parameters' effect.

Bad input (an unknown option or spec key, empty or inverted bounds, a log-scale bound <= 0, a
target the runs cannot give, a missing scene, bed or solver, a key gpudem-mpi refuses) exits 2
before anything runs, naming the option, or the spec's file, line and key; a failed run exits 1.
A run stopped as unstable (the solver's exit 3) is stored without targets, scored as the worst
evaluation that ran through so far once its batch is done, and the calibration goes on.
"""
import argparse
import concurrent.futures
import dataclasses
import hashlib
import json
import math
import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys
import threading
import time
import tomllib

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import calibration_optimizers as optimizers  # noqa: E402
import calibration_sensitivity  # noqa: E402
import plot_draft  # noqa: E402
from tillage_study import GEOMETRY_KEYS  # noqa: E402
from tool_travel import (SceneError, cross, find_tool, load_scene, steady_window,  # noqa: E402
                         unit)

PROJECT = pathlib.Path(__file__).resolve().parent.parent
QUANTITIES = {"draft_mean": "N", "draft_std": "N", "bed_height": "m"}
DRAFT_QUANTITIES = ("draft_mean", "draft_std")
SPEC_KEYS = {"calibration": {"scene", "bed", "bed_scene", "tool", "window", "set", "bed_set"},
             "parameter": {"name", "key", "min", "max", "log", "bed"},
             "target": {"quantity", "value", "sigma"}}
# Keys the calibration sets on every run itself.
OWN_KEYS = re.compile(r"simulation\.end_time|insert\.\d+\.bed|preparation\.bed_file|output\.dir")
RESULTS = "evaluations.jsonl"
PLOT_EVERY_S = 60.0


class CalibrationError(Exception):
    """Bad input, found before anything runs (exit 2)."""


EXIT_UNSTABLE = 3  # gpudem-mpi's exit code for a run stopped as unstable (docs/input.md)


class RunFailed(Exception):
    """A solver run that failed (exit 1)."""


# ---------------------------------------------------------------------------- the spec file

@dataclasses.dataclass(frozen=True)
class Parameter:
    name: str
    keys: tuple
    low: float
    high: float
    log: bool
    bed: bool

    def value(self, u):
        """The value at unit coordinate u (0 at min, 1 at max)."""
        if self.log:
            return math.exp(math.log(self.low) + u * (math.log(self.high) - math.log(self.low)))
        return self.low + u * (self.high - self.low)

    def span(self):
        """The range in the unit's own scale: high − low, or ln(high/low) on a log scale."""
        return math.log(self.high / self.low) if self.log else self.high - self.low

    def settings(self, u):
        return [f"{key}={self.value(u)!r}" for key in self.keys]


@dataclasses.dataclass(frozen=True)
class Target:
    quantity: str
    value: float
    sigma: float


@dataclasses.dataclass
class Spec:
    path: pathlib.Path
    digest: str
    scene: pathlib.Path
    scene_data: dict
    bed: pathlib.Path
    bed_scene: pathlib.Path
    tool: object  # tool_travel.Tool, or None without draft targets
    window: tuple
    end_time: float
    settings: list
    bed_settings: list
    parameters: list
    targets: list

    def bed_parameters(self):
        return [p for p in self.parameters if p.bed]


class SpecReader:
    """Reads SPEC and names the file, line and key of what it refuses."""

    def __init__(self, path):
        self.path = pathlib.Path(path)
        if not self.path.is_file():
            raise CalibrationError(f"SPEC: no file {path}")
        self.text = self.path.read_text()
        try:
            self.data = tomllib.loads(self.text)
        except tomllib.TOMLDecodeError as error:
            raise CalibrationError(f"{self.path}: not TOML: {error}") from None

    def line(self, table, index, key):
        """The line of `key` in the index-th [table] or [[table]] (its header without key)."""
        header = re.compile(r"^\s*\[\[?\s*([\w.]+)\s*\]\]?")
        seen, inside, found = -1, False, None
        for number, text in enumerate(self.text.splitlines(), 1):
            match = header.match(text)
            if match:
                inside = match.group(1) == table
                seen += inside
                if inside and seen == index and key is None:
                    return number
                continue
            if inside and seen == index and re.match(rf"^\s*{re.escape(key or '')}\s*=", text):
                found = found or number
        return found or 1

    def error(self, table, index, key, problem):
        where = table if index is None else f"{table}.{index}"
        where += f".{key}" if key else ""
        line = self.line(table, index or 0, key)
        return CalibrationError(f"{self.path}:{line}: {where}: {problem}")

    def path_of(self, table, key, required=False):
        value = self.data.get(table, {}).get(key)
        if value is None:
            if required:
                raise self.error(table, None, None, f"no {key} (a file, relative to the spec)")
            return None
        if not isinstance(value, str):
            raise self.error(table, None, key, "expected a file name")
        path = (self.path.parent / value).resolve()
        if not path.is_file():
            raise self.error(table, None, key, f"no file {path}")
        return path

    def check_tables(self):
        for table, value in self.data.items():
            if table not in SPEC_KEYS:
                raise self.error(table, None, None, f"unknown table; a spec has "
                                 f"{', '.join(SPEC_KEYS)}")
            if isinstance(value, list) != (table != "calibration"):
                form = "[calibration]" if table == "calibration" else f"[[{table}]]"
                raise self.error(table, None, None, f"expected {form}")
            entries = value if isinstance(value, list) else [value]
            for index, entry in enumerate(entries):
                unknown = sorted(set(entry) - SPEC_KEYS[table])
                if unknown:
                    raise self.error(table, index if isinstance(value, list) else None,
                                     unknown[0], f"unknown key; allowed: "
                                     f"{', '.join(sorted(SPEC_KEYS[table]))}")

    def number(self, table, index, entry, key):
        value = entry.get(key)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(table, index, key, "expected a number")
        return float(value)

    def parameter(self, index, entry):
        keys = entry.get("key")
        keys = [keys] if isinstance(keys, str) else keys
        if not keys or not all(isinstance(k, str) and k for k in keys):
            raise self.error("parameter", index, "key", "expected a --set key or a list of them")
        for key in keys:
            if OWN_KEYS.fullmatch(key) or GEOMETRY_KEYS.fullmatch(key):
                raise self.error("parameter", index, "key", f"{key}: the calibration sets it "
                                 "itself or reads it from the scene file to find the tool's "
                                 "window; it cannot be calibrated")
        low = self.number("parameter", index, entry, "min")
        high = self.number("parameter", index, entry, "max")
        if not low < high:
            raise self.error("parameter", index, "max", f"empty or inverted bounds: min {low:g}"
                             f" is not below max {high:g}")
        log = entry.get("log", False)
        if log and low <= 0:
            raise self.error("parameter", index, "min", f"a log scale needs min > 0, got {low:g}")
        return Parameter(entry.get("name", keys[0]), tuple(keys), low, high, bool(log),
                         bool(entry.get("bed", False)))

    def target(self, index, entry):
        quantity = entry.get("quantity")
        if quantity not in QUANTITIES:
            raise self.error("target", index, "quantity", f"'{quantity}' is none of "
                             f"{', '.join(QUANTITIES)}")
        sigma = self.number("target", index, entry, "sigma")
        if sigma <= 0:
            raise self.error("target", index, "sigma", f"expected a number > 0, got {sigma:g}")
        return Target(quantity, self.number("target", index, entry, "value"), sigma)

    def settings(self, key):
        values = self.data.get("calibration", {}).get(key, [])
        if not isinstance(values, list):
            raise self.error("calibration", None, key, "expected a list of \"KEY=VALUE\"")
        for value in values:
            if not isinstance(value, str) or "=" not in value:
                raise self.error("calibration", None, key, f"{value!r}: expected KEY=VALUE")
            if OWN_KEYS.fullmatch(value.partition("=")[0]):
                raise self.error("calibration", None, key, f"{value}: the calibration sets "
                                 "this key itself")
        return values


def read_spec(path):
    """The checked spec of file `path`."""
    reader = SpecReader(path)
    reader.check_tables()
    scene = reader.path_of("calibration", "scene", required=True)
    bed, bed_scene = reader.path_of("calibration", "bed"), reader.path_of("calibration",
                                                                          "bed_scene")
    if bed and bed_scene:
        raise reader.error("calibration", None, "bed_scene", "give bed (a bed file for every "
                           "run) or bed_scene (the scene that makes it), not both")
    parameters = [reader.parameter(i, e) for i, e in enumerate(reader.data.get("parameter", []))]
    targets = [reader.target(i, e) for i, e in enumerate(reader.data.get("target", []))]
    if not parameters or not targets:
        raise reader.error("calibration", None, None, "a spec needs at least one [[parameter]] "
                           "and one [[target]]")
    check_unique(reader, parameters, targets, bed_scene)
    try:
        scene_data = load_scene(scene)
    except SceneError as error:
        raise reader.error("calibration", None, "scene", str(error)) from None
    tool, window, end = pass_window(reader, scene, scene_data, targets)
    digest = hashlib.sha256(json.dumps(reader.data, sort_keys=True).encode()).hexdigest()
    return Spec(reader.path, digest, scene, scene_data, bed, bed_scene, tool, window, end,
                reader.settings("set"), reader.settings("bed_set"), parameters, targets)


def check_unique(reader, parameters, targets, bed_scene):
    keys = [key for p in parameters for key in p.keys]
    for index, p in enumerate(parameters):
        if any(keys.count(key) > 1 for key in p.keys):
            raise reader.error("parameter", index, "key", "a key of another parameter too")
        if p.bed and not bed_scene:
            raise reader.error("parameter", index, "bed", "bed = true needs "
                               "calibration.bed_scene, the scene that makes the bed")
    quantities = [t.quantity for t in targets]
    for index, t in enumerate(targets):
        if quantities.count(t.quantity) > 1:
            raise reader.error("target", index, "quantity", f"{t.quantity} is a target twice")
        if t.quantity == "bed_height" and not bed_scene:
            raise reader.error("target", index, "quantity", "bed_height is measured on the bed "
                               "the calibration makes: it needs calibration.bed_scene")


def pass_window(reader, scene, scene_data, targets):
    """(tool, steady window, run end) of the pass: the tool only for draft targets; the
    window calibration.window, else the tool's pass through the bed (scripts/tool_travel.py)."""
    calibration = reader.data.get("calibration", {})
    end = scene_data.get("simulation", {}).get("end_time")
    if not isinstance(end, (int, float)):
        raise reader.error("calibration", None, "scene", f"{scene} has no simulation.end_time")
    if not any(t.quantity in DRAFT_QUANTITIES for t in targets):
        return None, None, float(end)
    try:
        tool = find_tool(scene_data, scene, calibration.get("tool", "sweep"))
    except SceneError as error:
        raise reader.error("calibration", None, "tool", f"a draft target needs the moving "
                           f"tool: {error}") from None
    window = calibration.get("window")
    if window is None:
        try:
            window = steady_window(tool, scene_data, end)
        except SceneError as error:
            raise reader.error("calibration", None, "scene", str(error)) from None
    elif (not isinstance(window, list) or len(window) != 2 or
          not all(isinstance(t, (int, float)) for t in window) or
          not 0 <= window[0] < window[1] <= end):
        raise reader.error("calibration", None, "window", f"expected [start, end] with "
                           f"0 <= start < end <= the scene's end_time {end:g} s")
    return tool, (float(window[0]), float(window[1])), float(window[1])


# ------------------------------------------------------------------------------ the options

def parse_args(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add = parser.add_argument
    add("spec", metavar="SPEC", help="the calibration spec (TOML)")
    add("--out", metavar="DIR", help="default: out/calibration/<SPEC's name>")
    add("--optimizer", choices=["bo", "de"], default="bo")
    add("--evaluations", type=int, metavar="N", help="default: 100 (bo), 2700 (de)")
    add("--seed", type=int, default=1)
    add("--population", type=int, default=60, metavar="NP", help="de: population size")
    add("--mutation", type=float, default=0.8, metavar="F", help="de: mutation factor")
    add("--crossover", type=float, default=0.5, metavar="CR", help="de: crossover rate")
    add("--batch", type=int, default=4, metavar="B", help="bo: proposals per batch")
    add("--initial", type=int, metavar="N", help="bo: Latin-hypercube start (default 2d + 2)")
    add("--jobs", type=int, metavar="J", help="runs at once (default 1; --slurm: no limit)")
    add("--np", type=int, default=1, help="MPI ranks per run")
    add("--solver", default=str(PROJECT / "build/gpudem-mpi"), metavar="PATH")
    add("--slurm", action="store_true", help="run each batch as a Slurm job array")
    add("--sbatch-args", default="", metavar="TEXT", help="--slurm: options for sbatch")
    add("--poll", type=float, default=30.0, metavar="S", help="--slurm: seconds between polls")
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--check", action="store_true", help="validate, run nothing")
    mode.add_argument("--sensitivity", action="store_true", help="analyse the stored runs")
    add("--run-sd", action="append", default=[], metavar="QUANTITY=SD",
        help="--sensitivity: the target's spread between runs that differ only in chance "
             "(e.g. bed realisations), the least noise of its fit (repeatable)")
    args = parser.parse_args(argv)
    if args.out is None:
        args.out = str(PROJECT / "out/calibration" / pathlib.Path(args.spec).stem)
    if args.evaluations is None:
        args.evaluations = 2700 if args.optimizer == "de" else 100
    return args


def run_sd(args, spec):
    """--run-sd as {quantity: standard deviation}, each quantity a target of the spec."""
    spreads = {}
    targets = [t.quantity for t in spec.targets]
    for text in args.run_sd:
        quantity, _, value = text.partition("=")
        try:
            spreads[quantity] = float(value)
        except ValueError:
            raise CalibrationError(f"--run-sd {text}: takes QUANTITY=SD, SD a number") from None
        if quantity not in targets:
            raise CalibrationError(f"--run-sd {text}: {quantity} is not a target of the spec "
                                   f"({', '.join(targets)})")
        if not spreads[quantity] > 0:
            raise CalibrationError(f"--run-sd {text}: SD takes a value > 0")
    return spreads


def check_options(args):
    positive = (("--evaluations", args.evaluations), ("--batch", args.batch),
                ("--initial", args.initial), ("--jobs", args.jobs), ("--np", args.np),
                ("--poll", args.poll))
    for option, value in positive:
        if value is not None and value <= 0:
            raise CalibrationError(f"{option} takes a value > 0, got {value}")
    if args.optimizer == "de":
        if args.population < 5:
            raise CalibrationError(f"--population takes at least 5, got {args.population}")
        if args.evaluations < args.population:
            raise CalibrationError(f"--evaluations {args.evaluations}: less than one "
                                   f"generation of --population {args.population}")
        if not 0 < args.mutation <= 2:
            raise CalibrationError(f"--mutation takes a value in (0, 2], got {args.mutation}")
        if not 0 <= args.crossover <= 1:
            raise CalibrationError(f"--crossover takes a value in [0, 1], got {args.crossover}")
    if args.sensitivity:
        return
    if args.run_sd:
        raise CalibrationError("--run-sd goes with --sensitivity")
    if not pathlib.Path(args.solver).is_file() or not os.access(args.solver, os.X_OK):
        raise CalibrationError(f"--solver: no executable file {args.solver}")
    args.solver = str(pathlib.Path(args.solver).resolve())
    if args.np > 1 and not args.slurm and not shutil.which("mpirun"):
        raise CalibrationError("--np: more than one rank needs mpirun, which is not on the PATH")
    if args.slurm and not shutil.which("sbatch"):
        raise CalibrationError("--slurm: sbatch is not on the PATH")


def solver_refusal(args, command):
    """gpudem-mpi --check's error on `command`, or None when it accepts it."""
    result = subprocess.run([args.solver, *command, "--check"], capture_output=True, text=True,
                            env=dict(os.environ, OMP_NUM_THREADS="1"))
    if result.returncode == 0:
        return None
    lines = (result.stderr + result.stdout).strip().splitlines()
    return next((line for line in lines if "error" in line), lines[-1] if lines else "")


def check_with_solver(args, spec):
    """gpudem-mpi --check on the bed scene and the pass with every parameter at its bounds;
    a refusal names the parameter whose key it is, or calibration.set/bed_set."""
    reader = SpecReader(spec.path)
    scenes = [(False, spec.parameters, spec.settings, check_pass_command)]
    if spec.bed_scene:
        scenes.append((True, spec.bed_parameters(), spec.bed_settings, check_bed_command))
    for on_bed, parameters, settings, command in scenes:
        for u in (0.0, 1.0):
            everything = settings + [s for p in parameters for s in p.settings(u)]
            refusal = solver_refusal(args, command(spec, everything))
            if refusal is None:
                continue
            for index, p in enumerate(spec.parameters):
                if p in parameters and solver_refusal(args, command(spec, p.settings(u))):
                    raise reader.error("parameter", index, "key", f"at {p.value(u):g}: "
                                       f"gpudem-mpi --check refuses it: {refusal}")
            table = "bed_set" if on_bed else "set"
            raise reader.error("calibration", None, table if settings else "scene",
                               f"gpudem-mpi --check refuses it: {refusal}")


def check_pass_command(spec, settings):
    """The pass checked on its own: with a bed made per set (none yet) its bed source stands
    in as one particle of the first material in the middle of the domain."""
    command = [str(spec.scene), "--output-dir", "/nonexistent"]
    index = bed_insert_index(spec)
    if spec.bed:
        settings = settings + [f"insert.{index}.bed=\"{spec.bed}\""]
    elif spec.bed_scene:
        low, high = spec.scene_data["domain"]["min"], spec.scene_data["domain"]["max"]
        middle = [(a + b) / 2 for a, b in zip(low, high)]
        material = spec.scene_data["material"][0]["name"]
        settings = settings + [f"insert.{index}={{region = {{min = {middle}, max = "
                               f"{[c + 1e-3 for c in middle]}}}, count = 1, radius = 1e-4, "
                               f"material = \"{material}\"}}"]
    return command + [word for s in settings for word in ("--set", s)]


def check_bed_command(spec, settings):
    return [str(spec.bed_scene), "--output-dir", "/nonexistent"] + \
        [word for s in settings for word in ("--set", s)]


def bed_insert_index(spec):
    """The index of the pass's [[insert]] bed source (needed with bed or bed_scene)."""
    if not (spec.bed or spec.bed_scene):
        return None
    for index, source in enumerate(spec.scene_data.get("insert", [])):
        if "bed" in source:
            return index
    raise SpecReader(spec.path).error("calibration", None, "scene", f"{spec.scene} has no "
                                      "[[insert]] bed source to start from the bed")


# --------------------------------------------------------------------------- the results file

def header(args, spec):
    settings = {"spec": spec.digest, "optimizer": args.optimizer, "seed": args.seed}
    if args.optimizer == "de":
        settings.update(population=args.population, mutation=args.mutation,
                        crossover=args.crossover)
    else:
        settings.update(batch=args.batch, initial=args.initial)
    return {"calibration": settings,
            "parameters": [dataclasses.asdict(p) for p in spec.parameters],
            "targets": [dataclasses.asdict(t) for t in spec.targets]}


def read_results(path):
    """(header, records) of results file `path`; a last line cut short by a kill is dropped
    from the file."""
    if not path.is_file():
        return None, []
    text = path.read_text()
    if text and not text.endswith("\n"):
        text = text[:text.rfind("\n") + 1]
        with open(path, "r+") as f:
            f.truncate(len(text.encode()))
    lines = [json.loads(line) for line in text.splitlines() if line.strip()]
    head = lines[0] if lines and "calibration" in lines[0] else None
    return head, [line for line in lines if "evaluation" in line]


def check_header(path, stored, wanted, spec_path):
    """Refuses a results file of another calibration, naming what differs."""
    if stored is None:
        return
    old, new = stored["calibration"], wanted["calibration"]
    if old.get("spec") != new["spec"]:
        raise CalibrationError(f"SPEC: {path} holds a calibration of another spec than "
                               f"{spec_path} (its parameters, targets or scenes changed); give "
                               "another --out")
    for key in new:
        if old.get(key) != new[key]:
            raise CalibrationError(f"--{key} {new[key]}: {path} holds a calibration with "
                                   f"--{key} {old.get(key)}; give that or another --out")


def ran_through(records):
    """The records of runs that ran through (a run stopped as unstable has no targets)."""
    return [r for r in records if r["targets"] is not None]


class Results:
    """The append-only file of finished evaluations, looked up by point."""

    def __init__(self, path, head):
        self.path = path
        stored, self.records = read_results(path)
        if stored is None:
            path.parent.mkdir(parents=True, exist_ok=True)
            self._append(head)
        self.by_point = {tuple(r["point"]): r for r in self.records}
        self.lock = threading.Lock()

    def _append(self, entry):
        with open(self.path, "a") as f:
            f.write(json.dumps(entry) + "\n")
            f.flush()
            os.fsync(f.fileno())

    def add(self, record):
        with self.lock:
            self._append(record)
            self.records.append(record)
            self.by_point[tuple(record["point"])] = record

    def best(self):
        return min(ran_through(self.records), key=lambda r: r["objective"], default=None)


# ------------------------------------------------------------------------------- the runs

@dataclasses.dataclass
class Job:
    """One solver run: its folder and its arguments after the executable."""
    folder: pathlib.Path
    arguments: list


def settings_words(settings):
    return [word for s in settings for word in ("--set", s)]


def bed_name(spec, point):
    values = [p.value(u) for p, u in zip(spec.parameters, point) if p.bed]
    return "b" + hashlib.sha1(repr(values).encode()).hexdigest()[:12]


def bed_job(spec, folder, point):
    settings = spec.bed_settings + [s for p, u in zip(spec.parameters, point) if p.bed
                                    for s in p.settings(u)]
    settings.append(f"preparation.bed_file=\"{folder / 'bed.h5'}\"")
    return Job(folder, [str(spec.bed_scene), "--quiet", "--output-dir", str(folder),
                        *settings_words(settings)])


def pass_job(spec, folder, point, bed_file):
    settings = spec.settings + [s for p, u in zip(spec.parameters, point)
                                for s in p.settings(u)]
    settings.append(f"simulation.end_time={spec.end_time!r}")
    if bed_file:
        settings.append(f"insert.{bed_insert_index(spec)}.bed=\"{bed_file}\"")
    return Job(folder, [str(spec.scene), "--quiet", "--output-dir", str(folder),
                        *settings_words(settings)])


def thread_count(args):
    if "OMP_NUM_THREADS" in os.environ:
        return os.environ["OMP_NUM_THREADS"]
    return str(max(1, (os.cpu_count() or 1) // ((args.jobs or 1) * args.np)))


class LocalRunner:
    """Runs jobs --jobs at a time on this machine."""

    def __init__(self, args):
        self.args = args

    def command(self, job):
        command = [self.args.solver, *job.arguments]
        if self.args.np > 1:
            command = ["mpirun", "-np", str(self.args.np), "--bind-to", "none", *command]
        return command

    def launch(self, job):
        env = dict(os.environ, OMP_NUM_THREADS=thread_count(self.args),
                   OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
        start = time.monotonic()
        with open(job.folder / "solver.log", "w") as log:
            code = subprocess.run(self.command(job), stdout=log, stderr=subprocess.STDOUT,
                                  env=env).returncode
        return code, time.monotonic() - start

    def run(self, jobs, finished):
        """Runs `jobs`, calling finished(job, exit code, seconds) as each ends."""
        with concurrent.futures.ThreadPoolExecutor(self.args.jobs or 1) as pool:
            futures = {pool.submit(self.launch, job): job for job in jobs}
            for future in concurrent.futures.as_completed(futures):
                finished(futures[future], *future.result())


class SlurmRunner:
    """Runs jobs as one Slurm job array per call: writes OUT/slurm/NAME.sbatch, submits it and
    polls the run folders for the exit code each task writes."""

    def __init__(self, args):
        self.args = args
        self.count = 0

    def script(self, name, jobs):
        throttle = f"%{self.args.jobs}" if self.args.jobs else ""
        folder = pathlib.Path(self.args.out).resolve() / "slurm"
        lines = ["#!/usr/bin/env bash",
                 "# One gpudem-mpi run per array task, written by scripts/calibrate.py --slurm;",
                 "# each task writes the solver's exit code to exit_code in its run folder.",
                 f"#SBATCH --job-name={name}",
                 f"#SBATCH --array=0-{len(jobs) - 1}{throttle}",
                 f"#SBATCH --ntasks={self.args.np}",
                 f"#SBATCH --output={folder / name}-%a.out",
                 "set -uo pipefail",
                 "export OMP_NUM_THREADS=${SLURM_CPUS_PER_TASK:-1}",
                 "case $SLURM_ARRAY_TASK_ID in"]
        for index, job in enumerate(jobs):
            words = " ".join(shlex.quote(w) for w in [self.args.solver, *job.arguments])
            lines.append(f"  {index}) folder={shlex.quote(str(job.folder))}; "
                         f"command=({words}) ;;")
        lines += ["esac",
                  'cd "$folder"',
                  'srun --cpus-per-task="$OMP_NUM_THREADS" "${command[@]}" > solver.log 2>&1',
                  "echo $? > exit_code.part && mv exit_code.part exit_code", ""]
        return "\n".join(lines)

    def submit(self, jobs):
        self.count += 1
        name = f"calibrate-{self.count:04d}"
        path = pathlib.Path(self.args.out, "slurm", f"{name}.sbatch")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(self.script(name, jobs))
        result = subprocess.run(["sbatch", "--parsable", *shlex.split(self.args.sbatch_args),
                                 str(path)], capture_output=True, text=True)
        if result.returncode != 0:
            raise RunFailed(f"sbatch {path} failed: {result.stderr.strip()}")
        return result.stdout.strip().split(";")[0]

    def running(self, job_id):
        result = subprocess.run(["squeue", "-h", "-j", job_id], capture_output=True, text=True)
        return result.returncode == 0 and result.stdout.strip() != ""

    def run(self, jobs, finished):
        start = time.monotonic()
        job_id = self.submit(jobs)
        waiting = list(jobs)
        while waiting:
            alive = self.running(job_id)  # asked first: a task that ends now leaves its code
            for job in list(waiting):
                marker = job.folder / "exit_code"
                if marker.is_file():
                    waiting.remove(job)
                    finished(job, int(marker.read_text()), time.monotonic() - start)
            if waiting and not alive:
                for job in waiting:
                    finished(job, -1, time.monotonic() - start)
                return
            if waiting:
                time.sleep(self.args.poll)


# ----------------------------------------------------------------------------- the targets

def draft_series(spec, folder):
    """Times and draft of the pass in `folder` (scripts/plot_draft.py's draft)."""
    rows = plot_draft.read_rows(folder / "timeseries.csv", spec.tool.name)
    time_s, forces = plot_draft.components(rows, spec.tool.name, spec.tool.travel, spec.tool.up)
    return time_s, forces["draft"]


def bed_height(bed_file, up):
    """The median over square columns (4 mean diameters wide) of the bed's horizontal extent
    of the highest particle top (centre + radius along `up`) in each column."""
    with h5py.File(bed_file, "r") as f:
        particles = f["position_radius"][:]
    up = np.array(unit(up))
    across = np.array(unit(cross(up, (1.0, 0.0, 0.0)) if abs(up[0]) < 0.9
                           else cross(up, (0.0, 1.0, 0.0))))
    along = np.cross(across, up)
    width = 8 * particles[:, 3].mean()
    columns = np.floor(np.stack([particles[:, :3] @ along, particles[:, :3] @ across], 1) / width)
    tops = particles[:, :3] @ up + particles[:, 3]
    highest = {}
    for column, top in zip(map(tuple, columns), tops):
        highest[column] = max(top, highest.get(column, -np.inf))
    return float(np.median(list(highest.values())))


def measure(spec, folder, bed_file):
    """The targets' quantities of the pass in `folder` and its bed."""
    values = {}
    if spec.tool is not None:
        time_s, draft = draft_series(spec, folder)
        steady = [d for t, d in zip(time_s, draft) if spec.window[0] <= t <= spec.window[1]]
        if not steady:
            raise RunFailed(f"{folder / 'timeseries.csv'} has no row in the window "
                            f"{spec.window[0]:g}–{spec.window[1]:g} s")
        values["draft_mean"], values["draft_std"] = plot_draft.mean_std(steady)
    if any(t.quantity == "bed_height" for t in spec.targets):
        gravity = load_scene(spec.bed_scene).get("simulation", {}).get("gravity", [0, 0, -9.81])
        values["bed_height"] = bed_height(bed_file, [-g for g in gravity])
    return {t.quantity: values[t.quantity] for t in spec.targets}


def objective(spec, values):
    return sum(((values[t.quantity] - t.value) / t.sigma) ** 2 for t in spec.targets)


# --------------------------------------------------------------------------- the evaluator

def solver_identity(solver):
    """(version, commit): `solver --version`, and the git commit of the source tree it was
    built from (named by its build folder's CMakeCache.txt, else the folder holding it) as
    that tree is now; None outside git."""
    version = subprocess.run([solver, "--version"], capture_output=True, text=True).stdout
    folder = pathlib.Path(solver).resolve().parent
    cache = folder / "CMakeCache.txt"
    if cache.is_file():
        source = re.search(r"^CMAKE_HOME_DIRECTORY:INTERNAL=(.*)$", cache.read_text(), re.M)
        folder = pathlib.Path(source.group(1)) if source else folder
    commit = subprocess.run(["git", "-C", str(folder), "describe", "--always", "--dirty",
                             "--abbrev=12"], capture_output=True, text=True)
    return version.strip(), commit.stdout.strip() if commit.returncode == 0 else None


class Evaluator:
    """evaluate(points) for the optimizers: each point looked up in the results file, the
    others run (their beds first) and appended to it."""

    def __init__(self, args, spec, results, runner):
        self.args, self.spec, self.results, self.runner = args, spec, results, runner
        self.out = pathlib.Path(args.out).resolve()
        self.requested = 0
        self.seconds = []
        self.version, self.commit = solver_identity(args.solver)
        self.failures = []
        self.unstable = []
        self.bed_seconds = {}
        self.plotted = 0.0

    def __call__(self, points):
        points = [tuple(float(u) for u in p) for p in points]
        numbers = list(range(self.requested, self.requested + len(points)))
        self.requested += len(points)
        todo = {}
        for number, point in zip(numbers, points):
            if point not in self.results.by_point and point not in todo.values():
                todo[number] = point
        replayed = len(points) - len(todo)
        if replayed:
            print(self.progress(f"{replayed} evaluation(s) found in {RESULTS}",
                                numbers[-1] + 1 - len(todo)), flush=True)
        if todo:
            self.run(todo)
        if time.monotonic() - self.plotted > PLOT_EVERY_S:
            write_outputs(self.args, self.spec, self.results)
            self.plotted = time.monotonic()
        return [self.results.by_point[p]["objective"] for p in points]

    def beds(self, todo):
        """Makes the beds `todo` needs that are not made yet; {point: bed file}."""
        if not self.spec.bed_scene:
            return {point: self.spec.bed for point in todo.values()}
        folders = {p: self.out / "beds" / bed_name(self.spec, p) for p in todo.values()}
        jobs = {}
        charged = {r["bed"] for r in self.results.records}
        for point, folder in folders.items():
            if not (folder / "bed.json").is_file():
                if folder not in jobs:
                    jobs[folder] = bed_job(self.spec, folder, point)
            elif str(folder.relative_to(self.out)) not in charged:  # made before a restart
                made = json.loads((folder / "bed.json").read_text())
                self.bed_seconds.setdefault(folder, made.get("seconds", 0.0))
        self.start_jobs(jobs.values())
        self.runner.run(list(jobs.values()), self.bed_finished)
        self.stop_on_failure()
        return {point: folder / "bed.h5" for point, folder in folders.items()}

    def bed_finished(self, job, code, seconds):
        if code != 0 or not (job.folder / "bed.h5").is_file():
            self.failures.append(failure_text(job, code))
            return
        self.bed_seconds[job.folder] = seconds
        (job.folder / "bed.json").write_text(
            json.dumps({"arguments": job.arguments, "seconds": round(seconds, 3)}) + "\n")

    def run(self, todo):
        beds = self.beds(todo)
        jobs = {}
        for number, point in todo.items():
            folder = self.out / "runs" / f"e{number:05d}"
            jobs[folder] = (number, point, beds[point])
        pass_jobs = [pass_job(self.spec, folder, point, bed)
                     for folder, (_, point, bed) in jobs.items()]
        self.start_jobs(pass_jobs)
        self.pending = len(pass_jobs)

        def finished(job, code, seconds):
            number, point, bed = jobs[job.folder]
            self.pass_finished(job, code, seconds, number, point, bed)

        self.runner.run(pass_jobs, finished)
        self.stop_on_failure()
        self.store_unstable()

    def start_jobs(self, jobs):
        for job in jobs:
            shutil.rmtree(job.folder, ignore_errors=True)
            job.folder.mkdir(parents=True)
            (job.folder / "run.json").write_text(json.dumps({"arguments": job.arguments}) + "\n")

    def pass_finished(self, job, code, seconds, number, point, bed):
        self.pending -= 1
        if code == EXIT_UNSTABLE:
            self.unstable.append((number, point, bed, job, seconds))
            return
        try:
            if code != 0:
                raise RunFailed(failure_text(job, code))
            values = measure(self.spec, job.folder, bed)
        except (RunFailed, OSError, ValueError, KeyError) as error:
            self.failures.append(str(error))
            return
        self.store(number, point, bed, job, seconds, values, objective(self.spec, values))

    def store(self, number, point, bed, job, seconds, values, value, unstable=None):
        """Appends the record of evaluation `number`: its targets `values` (None for a run
        stopped as unstable, whose reason `unstable` is kept) and objective `value`."""
        bed_seconds = self.bed_seconds.pop(bed.parent, 0.0) if self.spec.bed_scene else 0.0
        record = {"evaluation": number, "point": list(point),
                  "parameters": {p.name: p.value(u) for p, u in zip(self.spec.parameters, point)},
                  "targets": values, "objective": value,
                  "wall_s": round(seconds + bed_seconds, 3),
                  "run": str(job.folder.relative_to(self.out)),
                  "bed": str(bed.parent.relative_to(self.out)) if self.spec.bed_scene else None,
                  "solver": self.version, "commit": self.commit}
        if unstable:
            record["unstable"] = unstable
        self.results.add(record)
        self.seconds.append(seconds + bed_seconds)
        shown = ", ".join(f"{q} {v:.4g}" for q, v in values.items()) if values else \
            "unstable, scored as the worst evaluation"
        print(self.progress(f"evaluation {number}: objective {value:.4g} ({shown}, "
                            f"{seconds + bed_seconds:.0f} s)", self.requested - self.pending),
              flush=True)

    def store_unstable(self):
        """Stores the batch's runs that stopped as unstable with the objective of the worst
        evaluation that ran through (taken once the batch is done, so a resumed calibration
        scores them the same); the calibration goes on around them."""
        if not self.unstable:
            return
        through = [r["objective"] for r in ran_through(self.results.records)]
        if not through:
            raise RunFailed("no evaluation has run through yet to score unstable runs by:\n" +
                            "\n".join(failure_text(job, EXIT_UNSTABLE)
                                       for *_, job, _ in self.unstable))
        for number, point, bed, job, seconds in sorted(self.unstable, key=lambda u: u[0]):
            self.store(number, point, bed, job, seconds, None, max(through),
                       unstable=last_line(job.folder / "solver.log"))
        self.unstable = []

    def progress(self, what, done):
        best = self.results.best()
        left = self.args.evaluations - done
        if not left:
            eta = "all done"
        elif self.seconds:
            parallel = min(self.args.jobs or left, left)
            eta = f"ETA {np.mean(self.seconds) * left / parallel / 60:.1f} min"
        else:
            eta = "ETA once a run is timed"
        best_text = f"best {best['objective']:.4g} (evaluation {best['evaluation']})" \
            if best else "no best yet"
        return f"[{done}/{self.args.evaluations}] {what}; {best_text}; {eta}"

    def stop_on_failure(self):
        if self.failures:
            raise RunFailed("\n".join(self.failures))


def last_line(path):
    lines = path.read_text().splitlines() if path.is_file() else []
    return lines[-1] if lines else ""


def failure_text(job, code):
    log = job.folder / "solver.log"
    tail = log.read_text().splitlines()[-5:] if log.is_file() else []
    return f"run {job.folder} failed (exit {code}); {log} ends:\n" + "\n".join(tail)


# ------------------------------------------------------------------------------- the plots

def write_outputs(args, spec, results):
    """best.json and the plots, from the evaluations stored so far."""
    out = pathlib.Path(args.out)
    records = sorted(results.records, key=lambda r: r["evaluation"])
    if not records:
        return
    best = results.best()
    (out / "best.json").write_text(json.dumps(best, indent=1) + "\n")
    plot_convergence(out / "convergence.png", records)
    plot_parameters(out / "parameters.png", spec, records, best)
    if spec.tool is not None and (out / best["run"] / "timeseries.csv").is_file():
        plot_best_draft(out / "best_draft.png", spec, out / best["run"], best)


def plot_convergence(path, records):
    numbers = [r["evaluation"] for r in records]
    values = [r["objective"] for r in records]
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(numbers, values, ".", color="0.6", label="evaluation")
    ax.step(numbers, np.minimum.accumulate(values), where="post", color="C3", label="best so far")
    ax.set_yscale("symlog", linthresh=1.0)
    ax.set_ylim(bottom=0)
    ax.set_xlabel("evaluation")
    ax.set_ylabel("objective Σ((sim − measured)/σ)²")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_parameters(path, spec, records, best):
    columns = min(3, len(spec.parameters))
    rows = math.ceil(len(spec.parameters) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(4 * columns, 3.2 * rows), squeeze=False)
    through = ran_through(records)
    unstable = [r for r in records if r["targets"] is None]
    for ax, p in zip(axes.flat, spec.parameters):
        ax.plot([r["parameters"][p.name] for r in through], [r["objective"] for r in through],
                ".", color="0.5")
        ax.plot([r["parameters"][p.name] for r in unstable], [r["objective"] for r in unstable],
                "x", color="0.5")
        ax.plot(best["parameters"][p.name], best["objective"], "*", color="C3", ms=12)
        ax.set_xscale("log" if p.log else "linear")
        ax.set_xlim(p.low, p.high)
        ax.set_yscale("symlog", linthresh=1.0)
        ax.set_ylim(bottom=0)
        ax.set_xlabel(p.name)
        ax.grid(alpha=0.3)
    for ax in axes.flat[len(spec.parameters):]:
        ax.set_visible(False)
    axes[0, 0].set_ylabel("objective")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_best_draft(path, spec, folder, best):
    time_s, draft = draft_series(spec, folder)
    start, end = spec.window
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(time_s, draft, lw=0.8, label=f"draft, evaluation {best['evaluation']}")
    mean = best["targets"].get("draft_mean")
    if mean is not None:
        ax.hlines(mean, start, end, colors="C3", lw=2, label=f"mean {mean:.1f} N")
    for target in spec.targets:
        if target.quantity == "draft_mean":
            ax.axhspan(target.value - target.sigma, target.value + target.sigma, color="C2",
                       alpha=0.25, label=f"measured {target.value:g} ± {target.sigma:g} N")
    ax.axvspan(start, end, color="0.9", zorder=0, label="steady window")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("draft [N]")
    ax.set_title("best set: " + ", ".join(f"{k} {v:.4g}" for k, v in best["parameters"].items()),
                 fontsize=8)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


# ------------------------------------------------------------------------------------ main

def optimize(args, spec, evaluate):
    dimensions = len(spec.parameters)
    if args.optimizer == "de":
        optimizers.differential_evolution(evaluate, dimensions, args.evaluations, args.seed,
                                          args.population, args.mutation, args.crossover)
    else:
        optimizers.bayesian(evaluate, dimensions, args.evaluations, args.seed, args.batch,
                            args.initial)


def prepare(args):
    spec = read_spec(args.spec)
    check_options(args)
    results_path = pathlib.Path(args.out, RESULTS)
    if args.sensitivity:
        return spec, None
    bed_insert_index(spec)
    stored, _ = read_results(results_path)
    check_header(results_path, stored, header(args, spec), args.spec)
    check_with_solver(args, spec)
    return spec, results_path


def analyse(spec, records, seed, spreads):
    """calibration_sensitivity.sensitivity, its refusal as a CalibrationError."""
    try:
        return calibration_sensitivity.sensitivity(spec, records, seed, spreads)
    except ValueError as error:
        raise CalibrationError(str(error)) from None


def main(argv=None):
    args = parse_args(argv)
    try:
        spec, results_path = prepare(args)
        if args.sensitivity:
            _, records = read_results(pathlib.Path(args.out, RESULTS))
            result = analyse(spec, ran_through(records), args.seed, run_sd(args, spec))
    except CalibrationError as error:
        print(f"calibrate.py: {error}", file=sys.stderr)
        return 2
    if args.sensitivity:
        calibration_sensitivity.print_sensitivity(spec, result, QUANTITIES)
        pathlib.Path(args.out, "sensitivity.json").write_text(json.dumps(result, indent=1))
        return 0
    if args.check:
        print(f"calibrate.py: {args.spec} and the options are valid")
        return 0
    results = Results(results_path, header(args, spec))
    runner = SlurmRunner(args) if args.slurm else LocalRunner(args)
    print(f"calibration: {args.optimizer}, {args.evaluations} evaluations of "
          f"{len(spec.parameters)} parameters in {args.out} ({len(results.records)} stored)",
          flush=True)
    try:
        optimize(args, spec, Evaluator(args, spec, results, runner))
    except RunFailed as error:
        write_outputs(args, spec, results)
        print(f"calibrate.py: {error}", file=sys.stderr)
        return 1
    write_outputs(args, spec, results)
    best = results.best()
    print(f"best: evaluation {best['evaluation']}, objective {best['objective']:.4g}: " +
          ", ".join(f"{k} = {v:.6g}" for k, v in best["parameters"].items()) +
          f"; written to {pathlib.Path(args.out, 'best.json')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
