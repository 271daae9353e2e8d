#!/usr/bin/env python3
"""scripts/tillage_study.py on a stand-in solver (fake_gpudem_mpi.py), a grid of depths 0.05 and
0.1 m, speeds 0.5 and 1 m/s and material.0.density 1000 and 2000, from a bed whose highest centre
is at 0.15 m. The tool is 0.2 m long, its front at x = −0.01 in the bin x = 0..1, moving from
t = 0.05 s, so its steady window runs from its front 0.2 m into the bed (after 0.21 m) to its
front 0.2 m before the far face (after 0.81 m): 0.47–1.67 s at 0.5 m/s (400 rows of 0.003 s),
0.26–0.86 s at 1 m/s (200 rows). The stand-in's force over that window is draft 1000 D + 50 V,
vertical −400 D and lateral 10 V, times ρ/1000, at depth D and speed V (steady: standard
deviation 0); the table must hold exactly that.
Resuming: the study is killed while its third run hangs; the two runs done are kept, and the next
invocation runs only the six others (the killed one with --resume and checkpoints, so that the
real solver would continue it from its last checkpoint); a third one runs nothing. Settings that change a finished
run's command line (--end-time), and bad input (an unknown option, an empty grid, a grid axis
without values, a tool that does not move, a missing bed, a speed without a steady window, a key
the study sets itself or reads from the scene, two grid points with one run folder) are refused with exit 2 before any run; a run that fails stops the study
with exit 1, naming it.
usage: check_tillage_study.py PROJECT_SOURCE_DIR WORK_DIR"""
import csv
import json
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import time

import h5py

project, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
LOG = work / "solver_calls.log"
LOG.touch()
(work / "tool.stl").write_text(
    "solid tool\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex -0.2 0.05 0\n"
    "vertex -0.2 -0.05 0.1\nendloop\nendfacet\nendsolid tool\n")
SCENE = ('[simulation]\nend_time = 5.0\n\n[domain]\nmin = [0, 0, 0]\nmax = [1, 0.5, 0.5]\n\n'
         '[[mesh]]\nname = "sweep"\nfile = "tool.stl"\noffset = [-0.01, 0.25, 0.07]\n\n'
         '[mesh.motion]\ntimes = [0.05, 5.0]\nvelocities = [[VELOCITY], [VELOCITY]]\n\n'
         '[[insert]]\nbed = "elsewhere.h5"\n')
(work / "till.toml").write_text(SCENE.replace("VELOCITY", "0.5, 0, 0"))
(work / "still.toml").write_text(SCENE.replace("VELOCITY", "0, 0, 0"))
with h5py.File(work / "bed.h5", "w") as bed:
    bed["position_radius"] = [[0.5, 0.25, 0.05, 0.01], [0.3, 0.2, 0.15, 0.01]]
GRID = ["--depth", "0.05", "0.1", "--speed", "0.5", "1", "--vary", "material.0.density", "1000",
        "2000"]
failures = []


def study(*args, out="study", hang=None, fail=None, wait=True):
    command = ["/usr/bin/python3", str(project / "scripts" / "tillage_study.py"),
               "--scene", str(work / "till.toml"), "--bed", str(work / "bed.h5"),
               "--solver", str(project / "tests" / "scripts" / "fake_gpudem_mpi.py"),
               "--out", str(work / out), *args]
    env = dict(os.environ, FAKE_GPUDEM_LOG=str(LOG), FAKE_GPUDEM_HANG=hang or "",
               FAKE_GPUDEM_FAIL=fail or "")
    if not wait:
        return subprocess.Popen(command, env=env, start_new_session=True,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    result = subprocess.run(command, env=env, capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


def calls():
    return LOG.read_text().split()


def kill_while_hanging(name):
    """Starts the study and kills it, solver and all, once the run `name` has started."""
    process = study(*GRID, hang=name, wait=False)
    deadline = time.monotonic() + 60
    while name not in calls() and time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.1)
    os.killpg(process.pid, signal.SIGKILL)
    process.wait()


def name(depth, speed, density):
    return f"depth{depth}-speed{speed}-material.0.density={density}"


WINDOWS = {"0.5": (0.47, 1.67, 400), "1": (0.26, 0.86, 200)}
RUNS = [(d, v, rho) for d in ("0.05", "0.1") for v in ("0.5", "1") for rho in ("1000", "2000")]


def expected_row(depth, speed, density):
    d, v, scale = float(depth), float(speed), float(density) / 1000
    start, end, rows = WINDOWS[speed]
    return {"depth_m": d, "speed_m_per_s": v, "material.0.density": float(density),
            "window_start_s": start, "window_end_s": end, "rows": rows,
            "draft_mean_N": (1000 * d + 50 * v) * scale, "draft_std_N": 0,
            "vertical_mean_N": -400 * d * scale, "vertical_std_N": 0,
            "lateral_mean_N": 10 * v * scale, "lateral_std_N": 0}


def check_table(runs):
    """study.csv holds the rows of `runs`, in order, with the stand-in's numbers."""
    with open(work / "study" / "study.csv", newline="") as f:
        table = list(csv.DictReader(f))
    if [row["run"] for row in table] != [name(*run) for run in runs]:
        failures.append(f"table runs {[row['run'] for row in table]}, wanted {runs}")
        return
    for row, run in zip(table, runs):
        for column, wanted in expected_row(*run).items():
            if abs(float(row[column]) - wanted) > 1e-5 * max(1, abs(wanted)):
                failures.append(f"{name(*run)}: {column} = {row[column]}, wanted {wanted}")


kill_while_hanging(name(*RUNS[2]))
done = sorted(p.parent.name for p in (work / "study" / "runs").glob("*/forces.json"))
if calls() != [name(*run) for run in RUNS[:3]] or done != sorted(name(*r) for r in RUNS[:2]):
    failures.append(f"killed at the third run: solver calls {calls()}, finished {done}")
check_table(RUNS[:2])

code, out = study(*GRID)
if code != 0 or calls()[3:] != [name(*run) for run in RUNS[2:]]:
    failures.append(f"resumed: exit {code}, solver calls {calls()[3:]}: {out}")
if f"[8/8] {name(*RUNS[-1])}: draft 300 ± 0 N over 0.26–0.86 s (ran in" not in out or \
        "[2/8]" not in out or "done before" not in out:
    failures.append(f"resumed: progress lines missing from {out!r}")
check_table(RUNS)
record = json.loads((work / "study" / "runs" / name(*RUNS[2]) / "run.json").read_text())
if not {"--resume", "checkpoint.every=0.1"} <= set(record["solver_args"]):
    failures.append(f"the killed run does not continue from its checkpoint: {record}")
for plot in ("forces_vs_depth.png", "forces_vs_speed.png"):
    if not (work / "study" / plot).is_file():
        failures.append(f"no {plot}")

code, out = study(*GRID)
if code != 0 or len(calls()) != 9 or out.count("done before") != 8:
    failures.append(f"all done: exit {code}, {len(calls())} solver calls: {out}")

REFUSED = [
    (["--end-time", "1"], "runs/depth0.05-speed0.5-material.0.density=1000 was run with other"),
    (["--dpth", "0.1"], "unrecognized arguments: --dpth"),
    (["--depth"], "argument --depth: expected at least one argument"),
    (["--vary", "material.0.young"], "--vary material.0.young: no values (an empty grid)"),
    (["--scene", str(work / "still.toml")], "mesh 'sweep' of"),
    (["--bed", str(work / "none.h5")], f"--bed: no file {work / 'none.h5'}"),
    (["--speed", "0.1", "--end-time", "1"], "--speed 0.1: no steady window"),
    (["--set", "simulation.end_time=2"], "simulation.end_time: the study sets this key itself"),
    (["--vary", "mesh.0.scale", "1", "2"], "mesh.0.scale: the study places the tool and finds"),
    (["--set", "domain.max=[1, 1, 1]"], "domain.max: the study places the tool and finds"),
    (["--depth", "0.05", "0.05000001"], "two grid points share the run folder name"),
]
for options, wanted in REFUSED:
    code, out = study(*GRID, *options)
    if code != 2 or wanted not in out or len(calls()) != 9:
        failures.append(f"{options}: exit {code}, {len(calls())} solver calls, "
                        f"'{wanted}' not in {out!r}")

code, out = study("--depth", "0.05", out="failing", fail="depth0.05-speed0.5")
if code != 1 or "run depth0.05-speed0.5 failed (exit 3)" not in out or \
        "a failure made on purpose" not in out:
    failures.append(f"a failed run: exit {code}: {out!r}")

for failure in failures:
    print(failure)
print(f"check_tillage_study: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
