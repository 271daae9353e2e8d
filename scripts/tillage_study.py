#!/usr/bin/python3
"""Runs a tillage tool over a grid of working depths and speeds (and of any other scene keys) from
one prepared bed, one gpudem-mpi run per grid point, and tabulates and plots the draft, vertical
and lateral force over each run's steady window.

Usage: scripts/tillage_study.py [--bed BED_H5] [--scene TOML] [--tool NAME] [--out DIR]
       [--depth M ...] [--speed M_PER_S ...] [--vary KEY VALUE ...]... [--set KEY=VALUE]...
       [--surface M] [--end-time S] [--entry-length M] [--exit-margin M]
       [--np N] [--solver PATH] [--checkpoint-every S]

Every run is the scene (default inputs/tillage/quickstart_till.toml) with its [[insert]] bed
source set to BED (default out/tillage-quickstart/bed/bed.h5, the one scripts/demo.sh makes),
and, for its grid point:
- depth D: the tool's [[mesh]] offset moved along the vertical so that the mesh's origin (the
  sweep's nose) lies D below the bed surface, the highest particle centre of BED (the trim
  height of a trimmed bed) unless --surface gives it; default: the scene's own placement;
- speed V: every [mesh.motion] velocity scaled by V over the tool's speed at its first moving
  keyframe, so the direction stays (a constant-speed pass runs at V); default: the scene's;
- each --vary KEY VALUE...: one axis of the grid over any key gpudem-mpi's --set takes;
  --set KEY=VALUE goes to every run.
Each run's steady window comes from the tool's travel (the rule of scripts/tool_travel.py, as in
scripts/plot_draft.py) and the run stops at the window's end: simulation.end_time is set to it,
never beyond the scene's end_time (or --end-time). A grid point without a window is refused.

Run k is written to OUT/runs/NAME (NAME from its values, e.g. depth0.08-speed0.7): the solver's
output and solver.log, run.json (its command line, written when it starts), forces.png and
forces.json (the window and the mean, standard deviation and row count of each force), written
last. The study resumes: a run with forces.json is done and not run again; any other starts with
gpudem-mpi --resume and checkpoints every --checkpoint-every s, so a killed run continues from
its last checkpoint. A run folder whose run.json holds another command line is refused. After each
run it prints "[done/total] ... ETA" and rewrites OUT/study.csv (one row per finished run); at the
end it plots OUT/forces_vs_depth.png and OUT/forces_vs_speed.png (mean ± standard deviation).
Bad input (an unknown option, an empty grid, a missing scene, bed or solver, a tool that does not
move, a grid point without a steady window) exits 2, naming it, before anything runs; a failed
run exits 1. One rank runs the solver directly, more through mpirun (as scripts/mpi-env.sh sets
it up); unless OMP_NUM_THREADS is set each rank gets an equal share of the cores.
"""
import argparse
import csv
import dataclasses
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import plot_draft  # noqa: E402
from tool_travel import SceneError, dot, find_tool, load_scene, steady_window  # noqa: E402

PROJECT = pathlib.Path(__file__).resolve().parent.parent
FORCES = ("draft", "vertical", "lateral")
STUDY_KEYS = re.compile(r"simulation\.end_time|checkpoint\.every|insert\.\d+\.bed|"
                        r"mesh\.\d+\.(offset|motion\.velocities)")
# Keys that move the tool, the bin or "up": the study reads them from the scene file to place
# the tool and find each run's steady window, so a run must not change them.
GEOMETRY_KEYS = re.compile(r"(mesh|implement|domain)\..*|simulation\.gravity")


class StudyError(Exception):
    """Bad input, found before anything runs (exit 2)."""


@dataclasses.dataclass
class Run:
    name: str
    depth: float
    speed: float
    varied: tuple  # ((key, value), ...)
    window: tuple
    solver_args: list


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add = parser.add_argument
    add("--scene", default=str(PROJECT / "inputs/tillage/quickstart_till.toml"), metavar="TOML")
    add("--bed", default=str(PROJECT / "out/tillage-quickstart/bed/bed.h5"), metavar="BED_H5")
    add("--tool", default="sweep", help="the [[mesh]] name of the tool")
    add("--out", default=str(PROJECT / "out/tillage-study"), metavar="DIR")
    add("--depth", nargs="+", type=float, metavar="M", help="depths below the bed surface")
    add("--speed", nargs="+", type=float, metavar="M_PER_S", help="speeds along the travel")
    add("--vary", nargs="+", action="append", default=[], metavar=("KEY", "VALUE"),
        help="a grid axis over a scene key: KEY then its values (TOML)")
    add("--set", action="append", default=[], metavar="KEY=VALUE", help="for every run")
    add("--surface", type=float, metavar="M", help="bed surface height (default: from BED)")
    add("--end-time", type=float, metavar="S", help="no run beyond S (default: the scene's)")
    add("--entry-length", type=float, metavar="M", help="default: the tool's length")
    add("--exit-margin", type=float, metavar="M", help="default: the tool's length")
    add("--np", type=int, default=1, help="MPI ranks per run")
    add("--solver", default=str(PROJECT / "build/gpudem-mpi"), metavar="PATH")
    add("--checkpoint-every", type=float, default=0.1, metavar="S")
    return parser.parse_args()


def check_options(args):
    """Refuses what the options alone get wrong."""
    for path, option in ((args.scene, "--scene"), (args.bed, "--bed"), (args.solver, "--solver")):
        if not pathlib.Path(path).is_file():
            raise StudyError(f"{option}: no file {path}")
    if not os.access(args.solver, os.X_OK):
        raise StudyError(f"--solver: {args.solver} is not executable")
    if args.np > 1 and not shutil.which("mpirun"):
        raise StudyError("--np: more than one rank needs mpirun, which is not on the PATH")
    given = (("--depth", args.depth), ("--speed", args.speed), ("--end-time", [args.end_time]),
             ("--np", [args.np]), ("--checkpoint-every", [args.checkpoint_every]))
    for option, values in given:
        if any(v is not None and v <= 0 for v in values or []):
            raise StudyError(f"{option} takes values > 0")
    for axis in args.vary:
        if len(axis) < 2:
            raise StudyError(f"--vary {axis[0]}: no values (an empty grid)")
    for setting in args.set:
        if "=" not in setting:
            raise StudyError(f"--set {setting}: expected KEY=VALUE")
    for key in [axis[0] for axis in args.vary] + [s.partition("=")[0] for s in args.set]:
        if STUDY_KEYS.fullmatch(key):
            raise StudyError(f"--set/--vary {key}: the study sets this key itself "
                             "(use --depth, --speed, --end-time or --bed)")
        if GEOMETRY_KEYS.fullmatch(key):
            raise StudyError(f"--set/--vary {key}: the study places the tool and finds its "
                             "steady window from the scene file; change this key there")


def bed_surface(bed, up):
    """The highest particle centre of bed file `bed` along `up`."""
    try:
        with h5py.File(bed, "r") as f:
            positions = f["position_radius"][:, :3]
    except (OSError, KeyError) as error:
        raise StudyError(f"--bed: cannot read particles from {bed}: {error}") from None
    if len(positions) == 0:
        raise StudyError(f"--bed: {bed} holds no particle")
    return float((positions @ up).max())


def bed_insert_index(scene, path):
    for index, source in enumerate(scene.get("insert", [])):
        if "bed" in source:
            return index
    raise StudyError(f"--scene: {path} has no [[insert]] bed source to start from the bed")


def scene_speed(tool):
    """The tool's speed along its travel at its first moving keyframe."""
    return next(s for s in tool.speeds() if s != 0)


def scene_depth(tool, surface):
    """The depth of the tool's origin below `surface` as the scene places it."""
    return surface - dot(tool.mesh.get("offset", [0.0, 0.0, 0.0]), tool.up)


def at_speed(tool, speed):
    """The tool with its keyframe velocities scaled to `speed` (12 significant digits)."""
    scale = speed / scene_speed(tool)
    return dataclasses.replace(tool, velocities=tuple(
        tuple(float(f"{c * scale:.12g}") for c in v) for v in tool.velocities))


def toml_vector(values):
    return "[" + ", ".join(repr(float(f"{v:.12g}")) for v in values) + "]"


def solver_args(args, tool, bed_index, point):
    """The command-line arguments (after the executable) of the run at `point`, `tool` moving
    at its speed."""
    depth, varied, end, out_dir = point
    rise = scene_depth(tool, args.surface_height) - depth
    offset = [c + rise * u for c, u in zip(tool.mesh.get("offset", [0.0, 0.0, 0.0]), tool.up)]
    velocities = ", ".join(toml_vector(v) for v in tool.velocities)
    settings = [f"simulation.end_time={end!r}", f"checkpoint.every={args.checkpoint_every!r}",
                f"insert.{bed_index}.bed=\"{pathlib.Path(args.bed).resolve()}\"",
                f"mesh.{tool.index}.offset={toml_vector(offset)}",
                f"mesh.{tool.index}.motion.velocities=[{velocities}]",
                *args.set, *(f"{key}={value}" for key, value in varied)]
    command = [str(pathlib.Path(args.scene).resolve()), "--quiet", "--resume",
               "--output-dir", str(out_dir)]
    return command + [word for s in settings for word in ("--set", s)]


def run_name(depth, speed, varied):
    name = f"depth{depth:g}-speed{speed:g}" + "".join(f"-{k}={v}" for k, v in varied)
    return re.sub(r"[^\w.+=-]", "_", name)


def grid(args, tool):
    """Every (depth, speed, varied) of the grid, depth slowest."""
    depths = args.depth or [scene_depth(tool, args.surface_height)]
    speeds = args.speed or [scene_speed(tool)]
    points = [(d, v, ()) for d in depths for v in speeds]
    for key, *values in args.vary:
        points = [(d, v, varied + ((key, value),)) for d, v, varied in points for value in values]
    return points


def plan_runs(args, scene, tool):
    """The runs of the study, each with its window and command line."""
    bed_index = bed_insert_index(scene, args.scene)
    run_end = args.end_time
    if run_end is None:
        run_end = scene.get("simulation", {}).get("end_time")
    if run_end is None:
        raise StudyError(f"--scene: {args.scene} has no simulation.end_time; give --end-time")
    runs = []
    for depth, speed, varied in grid(args, tool):
        moving = at_speed(tool, speed)
        try:
            window = steady_window(moving, scene, run_end, args.entry_length, args.exit_margin)
        except SceneError as error:
            raise StudyError(f"--speed {speed:g}: {error}") from None
        name = run_name(depth, speed, varied)
        point = (depth, varied, window[1], pathlib.Path(args.out, "runs", name).resolve())
        if any(run.name == name for run in runs):
            raise StudyError(f"two grid points share the run folder name {name}; give values "
                             "that differ in their first 6 significant digits and their "
                             "letters and digits")
        runs.append(Run(name, depth, speed, varied, window,
                        solver_args(args, moving, bed_index, point)))
    return runs


def check_earlier_runs(runs, out):
    """Refuses a run folder that an earlier study started with another command line."""
    for run in runs:
        record = pathlib.Path(out, "runs", run.name, "run.json")
        if record.is_file() and json.loads(record.read_text())["solver_args"] != run.solver_args:
            raise StudyError(f"{record.parent} was run with other settings (its run.json); "
                             "give another --out or remove that folder")


def prepare(args):
    """The checked inputs: (tool, runs)."""
    check_options(args)
    try:
        scene = load_scene(args.scene)
        tool = find_tool(scene, args.scene, args.tool)
    except SceneError as error:
        raise StudyError(f"--scene: {error}") from None
    if tool.in_implement:
        raise StudyError(f"--scene: mesh '{tool.name}' moves with an [[implement]]; the study "
                         "sets a mesh's own offset and [mesh.motion]")
    args.surface_height = args.surface
    if args.surface_height is None:
        args.surface_height = bed_surface(args.bed, tool.up)
    runs = plan_runs(args, scene, tool)
    check_earlier_runs(runs, args.out)
    return tool, runs


def launch(args, run, log):
    """Runs the solver for `run`, its output appended to `log`; returns its exit code."""
    env = dict(os.environ)
    env.setdefault("OMP_NUM_THREADS", str(max(1, (os.cpu_count() or 1) // args.np)))
    command = [args.solver, *run.solver_args]
    if args.np > 1:
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_rmaps_base_oversubscribe="1")
        command = ["mpirun", "-np", str(args.np), "--bind-to", "none", *command]
    with open(log, "a") as out:
        return subprocess.run(command, stdout=out, stderr=subprocess.STDOUT, env=env).returncode


def measure(run, run_dir, tool):
    """The forces of a finished run over its window: writes forces.png and forces.json."""
    rows = plot_draft.read_rows(run_dir / "timeseries.csv", tool.name)
    time_s, forces = plot_draft.components(rows, tool.name, tool.travel, tool.up)
    stats = plot_draft.plot(time_s, forces, run.window, tool.name, run_dir / "forces.png")
    result = {"window": list(run.window), **{name: list(stats[name]) for name in FORCES}}
    staging = run_dir / "forces.json.tmp"
    staging.write_text(json.dumps(result, indent=1) + "\n")
    staging.replace(run_dir / "forces.json")  # the mark of a finished run, written last
    return result


def run_once(args, run, tool):
    """The forces of `run`, running it first unless an earlier study finished it;
    (result, whether it ran)."""
    run_dir = pathlib.Path(args.out, "runs", run.name)
    if (run_dir / "forces.json").is_file():
        return json.loads((run_dir / "forces.json").read_text()), False
    run_dir.mkdir(parents=True, exist_ok=True)
    record = run_dir / "run.json.part"  # renamed once whole: a kill leaves no torn run.json
    record.write_text(json.dumps({"solver_args": run.solver_args}, indent=1))
    record.replace(run_dir / "run.json")
    code = launch(args, run, run_dir / "solver.log")
    if code != 0:
        tail = (run_dir / "solver.log").read_text().splitlines()[-5:]
        sys.exit(f"tillage_study.py: run {run.name} failed (exit {code}); "
                 f"{run_dir / 'solver.log'} ends:\n" + "\n".join(tail))
    return measure(run, run_dir, tool), True


def write_table(path, runs, results):
    keys = [key for key, _ in runs[0].varied]
    columns = ["run", "depth_m", "speed_m_per_s", *keys, "window_start_s", "window_end_s",
               "rows", *(f"{f}_{s}_N" for f in FORCES for s in ("mean", "std"))]
    with open(path, "w", newline="") as f:
        table = csv.writer(f)
        table.writerow(columns)
        for run in runs:
            if run.name not in results:
                continue
            result = results[run.name]
            table.writerow([run.name, f"{run.depth:g}", f"{run.speed:g}",
                            *(value for _, value in run.varied),
                            *(f"{t:.6g}" for t in result["window"]), result["draft"][2],
                            *(f"{result[f][k]:.6g}" for f in FORCES for k in (0, 1))])


def plot_against(path, runs, results, along):
    """Each force's mean ± std against depth or speed (`along`), a line per other setting."""
    fig, axes = plt.subplots(3, 1, figsize=(7, 8), sharex=True)
    lines = {}
    for run in runs:
        other = (run.speed if along == "depth" else run.depth, run.varied)
        lines.setdefault(other, []).append(run)
    for (value, varied), line in lines.items():
        label = (f"speed {value:g} m/s" if along == "depth" else f"depth {value:g} m") + \
            "".join(f", {k} = {v}" for k, v in varied)
        x = [getattr(run, along) for run in line]
        for ax, force in zip(axes, FORCES):
            ax.errorbar(x, [results[r.name][force][0] for r in line],
                        yerr=[results[r.name][force][1] for r in line],
                        marker="o", capsize=3, label=label)
    for ax, force in zip(axes, FORCES):
        ax.set_ylabel(f"{force} [N]")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[0].set_title("mean ± standard deviation over each run's steady window")
    axes[-1].set_xlabel("depth [m]" if along == "depth" else "speed [m/s]")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def progress(done, total, run, result, ran, seconds):
    """The line printed once a run is done; `seconds` of the runs made so far, for the ETA."""
    left = total - done
    eta = f"ETA {sum(seconds) / len(seconds) * left / 60:.1f} min" if seconds and left else \
        ("all done" if not left else "ETA once a run is timed")
    mean, std, _ = result["draft"]
    how = f"ran in {seconds[-1]:.0f} s" if ran else "done before"
    return (f"[{done}/{total}] {run.name}: draft {mean:.4g} ± {std:.3g} N over "
            f"{result['window'][0]:.3g}–{result['window'][1]:.3g} s ({how}); {eta}")


def main():
    args = parse_args()
    try:
        tool, runs = prepare(args)
    except StudyError as error:
        print(f"tillage_study.py: {error}", file=sys.stderr)
        return 2
    print(f"tillage study: {len(runs)} runs in {args.out}; bed surface "
          f"{args.surface_height:.6g} m; tool '{tool.name}' along {tool.travel}", flush=True)
    results, seconds = {}, []
    for done, run in enumerate(runs, 1):
        start = time.monotonic()
        results[run.name], ran = run_once(args, run, tool)
        if ran:
            seconds.append(time.monotonic() - start)
        print(progress(done, len(runs), run, results[run.name], ran, seconds), flush=True)
        write_table(pathlib.Path(args.out, "study.csv"), runs, results)
    for along in ("depth", "speed"):
        plot_against(pathlib.Path(args.out, f"forces_vs_{along}.png"), runs, results, along)
    print(f"table: {pathlib.Path(args.out, 'study.csv')}; plots: forces_vs_depth.png, "
          "forces_vs_speed.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
