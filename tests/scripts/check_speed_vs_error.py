#!/usr/bin/python3
"""scripts/speed_vs_error.py with the real solver on the impact scene cut to 200 spheres, a grid
of dt_fraction 0.05 (the reference), 0.1 (the centre) and 0.2 in double precision.
The table must have its columns; the reference row errors 0 and the others finite errors > 0;
each row's restitution within 2 % of the scene's 0.5 and its contact duration between 1 and
1.2 times the elastic Hertz duration of a sphere on the floor, 2.868 (m² / (r E*² v))^{1/5}
(the damped contact lasts a little longer). The recommendation for each tolerance must be the
row of least wall time among those within it, as found here from the table.
The pure functions on synthetic rows: recommend() and pareto_front() with known answers, and
solver_timing() on the last line of a fixed and of an adaptive run.
Resuming: a sweep with --repeat 2 is killed (SIGKILL, it and the solver) once two runs are done,
and run again: the runs done are kept (their result.json untouched), the others run, and the
table's points and observables equal those of an uninterrupted sweep.
Several beds: table_rows() on synthetic runs of two points on two beds gives each observable's
mean over the beds, its error and the standard error of the paired differences, as computed
here by hand; and a real silo sweep (two points) on two small beds poured with different seeds
runs each point on each bed and tables their means.
Refusals (exit 2, naming the option, before any run): an unknown scene type, an axis without
values, a dt_fraction the solver refuses (a skin it refuses), --scale on the impact scene, a
--set key the study sets, a missing bed, a bed given twice.
usage: check_speed_vs_error.py PROJECT_SOURCE_DIR WORK_DIR GPUDEM_MPI"""
import csv
import json
import math
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import time

project, work, solver = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]), sys.argv[3]
sys.path.insert(0, str(project / "scripts"))
import speed_vs_error  # noqa: E402

shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
failures = []
GRID = ["--dt-fraction", "0.05", "0.2", "--precision", "double", "--skin", "auto",
        "--integrator", "velocity_verlet", "--step", "auto", "--set", "insert.0.count=200"]
POINTS = [f"dt{f}-double-skinauto-velocity_verlet-scale1" for f in ("0.05", "0.1", "0.2")]
ENV = dict(os.environ, OMP_NUM_THREADS="1")


def sweep(out, *options, wait=True):
    command = ["/usr/bin/python3", str(project / "scripts" / "speed_vs_error.py"), "impact",
               "--solver", solver, "--out", str(work / out), *options]
    if not wait:
        return subprocess.Popen(command, env=ENV, start_new_session=True,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    result = subprocess.run(command, env=ENV, capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


def read_table(out):
    with open(work / out / "table.csv", newline="") as f:
        return list(csv.DictReader(f))


def hertz_duration():
    """The elastic Hertz contact duration of the scene's sphere on its floor at 1 m/s."""
    r, density, e1, nu1, e2, nu2 = 2e-3, 2500.0, 5e6, 0.3, 2e8, 0.3
    mass = density * 4 / 3 * math.pi * r**3
    e_star = 1 / ((1 - nu1**2) / e1 + (1 - nu2**2) / e2)
    return 2.868 * (mass**2 / (r * e_star**2 * 1.0)) ** 0.2


def check_pure_functions():
    rows = [{"point": "a", "max_error": 0.0, "wall_s": 10.0, "particle_steps_per_s": 1e5},
            {"point": "b", "max_error": 0.004, "wall_s": 6.0, "particle_steps_per_s": 3e5},
            {"point": "c", "max_error": 0.03, "wall_s": 2.0, "particle_steps_per_s": 2e5},
            {"point": "d", "max_error": 0.2, "wall_s": 1.0, "particle_steps_per_s": 9e5},
            {"point": "e", "max_error": 0.01, "wall_s": 7.0, "particle_steps_per_s": 4e5},
            {"point": "f", "max_error": math.nan, "wall_s": 0.5, "particle_steps_per_s": 1e6}]
    wanted = [(0.01, "wall", "b"), (0.01, "rate", "e"), (0.05, "wall", "c"),
              (0.05, "rate", "e"), (0.001, "wall", "a"), (0.5, "wall", "d")]
    for tolerance, rank_by, point in wanted:
        got = speed_vs_error.recommend(rows, tolerance, rank_by)
        if got is None or got["point"] != point:
            failures.append(f"recommend({tolerance}, {rank_by}): {got and got['point']}, "
                            f"wanted {point}")
    if speed_vs_error.recommend(rows[2:4], 0.01) is not None:
        failures.append("recommend: a row beyond the tolerance was picked")
    speeds = [1.0, 2.0, 3.0, 4.0, 2.5, 3.0]
    errors = [0.001, 0.01, 0.005, 0.2, 0.02, 0.005]
    front = speed_vs_error.pareto_front(speeds, errors)
    if front != [0, 2, 5, 3]:  # 1 and 4 are beaten by 2; 2 and 5 are equal
        failures.append(f"pareto_front: {front}, wanted [0, 2, 5, 3]")
    split = speed_vs_error.solver_timing("done: 10 steps (base steps, split into 40) in 2.00 s; 0")
    fixed = speed_vs_error.solver_timing("done: 10 steps in 2.00 s; 0 particles removed")
    if split != (40, 2.0) or fixed != (10, 2.0):
        failures.append(f"solver_timing: {split} and {fixed}, wanted (40, 2.0) and (10, 2.0)")


def check_table(out):
    rows = read_table(out)
    columns = ["point", "reference", "dt_fraction", "precision", "skin", "integrator", "scale",
               "step", "dt_s", "particles", "steps", "repeats", "beds", "wall_s", "wall_s_min",
               "wall_s_max", "particle_steps_per_s", "restitution", "contact_duration_s",
               "restitution_error", "contact_duration_s_error", "restitution_error_se",
               "contact_duration_s_error_se", "max_error"]
    if not rows or list(rows[0]) != columns:
        failures.append(f"{out}: columns {list(rows[0]) if rows else None}, wanted {columns}")
        return rows
    if [row["point"] for row in rows] != POINTS:
        failures.append(f"{out}: points {[row['point'] for row in rows]}, wanted {POINTS}")
    duration = hertz_duration()
    for row in rows:
        errors = [float(row[c]) for c in ("restitution_error", "contact_duration_s_error",
                                          "max_error")]
        reference = row["point"] == POINTS[0]
        if row["reference"] != str(int(reference)) or (reference and any(errors)) or (
                not reference and not all(math.isfinite(e) and e > 0 for e in errors)):
            failures.append(f"{out}: {row['point']}: reference {row['reference']}, errors {errors}")
        if abs(float(row["restitution"]) - 0.5) > 0.01 or \
                not 1 <= float(row["contact_duration_s"]) / duration <= 1.2:
            failures.append(f"{out}: {row['point']}: e {row['restitution']}, duration "
                            f"{row['contact_duration_s']} s against Hertz {duration:.5g} s")
        rate = float(row["particles"]) * float(row["steps"]) / float(row["wall_s"])
        if int(row["particles"].split(".")[0]) != 200 or \
                abs(rate / float(row["particle_steps_per_s"]) - 1) > 1e-6:
            failures.append(f"{out}: {row['point']}: particles {row['particles']}, "
                            f"particle-steps/s {row['particle_steps_per_s']} against {rate}")
    return rows


def check_recommendation(out, rows):
    picks = json.loads((work / out / "recommendation.json").read_text())["recommended"]
    for tolerance in ("0.01", "0.05"):
        within = [r for r in rows if float(r["max_error"]) <= float(tolerance)]
        best = min(within, key=lambda r: float(r["wall_s"]))["point"]
        if (picks.get(tolerance) or {}).get("point") != best:
            failures.append(f"{out}: recommended within {tolerance}: {picks.get(tolerance)}, "
                            f"wanted {best}")


def kill_after(out, runs_done, *options):
    """Starts a sweep and kills it, solver and all, once `runs_done` runs are finished."""
    process = sweep(out, *options, wait=False)
    deadline = time.monotonic() + 60
    while len(list((work / out).glob("runs/*/result.json"))) < runs_done and \
            time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.05)
    os.killpg(process.pid, signal.SIGKILL)
    process.wait()


def check_bed_means():
    """Two points on two beds, x = 10.0 and 12.0 for the reference, 10.5 and 12.1 for the other:
    means 11.0 and 11.3, error 0.3 / 11, paired differences 0.5 and 0.1, standard error
    stdev / √2 = 0.2, relative 0.2 / 11."""
    reference = speed_vs_error.Point(0.05, "double", "auto", "velocity_verlet", 1.0)
    other = speed_vs_error.Point(0.1, "double", "auto", "velocity_verlet", 1.0)
    values = {(reference.name, 1): 10.0, (reference.name, 2): 12.0, (other.name, 1): 10.5,
              (other.name, 2): 12.1}
    results = {(name, bed, 1): {"steps": 100, "wall_s": 1.0, "particles": 10.0,
                                "observables": {"x": x}} for (name, bed), x in values.items()}
    checks = {p.name: {"dt_s": 1e-5} for p in (reference, other)}
    rows = speed_vs_error.table_rows([reference, other], reference, results, checks)
    ref, row = rows
    wanted = {"reference x": (ref["observables"]["x"], 11.0), "x": (row["observables"]["x"], 11.3),
              "error": (row["errors"]["x"], 0.3 / 11), "standard error": (row["error_se"]["x"],
                                                                           0.2 / 11),
              "reference error": (ref["errors"]["x"], 0.0), "beds": (row["beds"], 2)}
    for what, (got, expected) in wanted.items():
        if not math.isclose(got, expected, rel_tol=1e-12, abs_tol=1e-15):
            failures.append(f"two beds: {what} {got}, wanted {expected}")


def silo_beds():
    """Two small silo beds (300 grains) poured with seeds 1 and 2."""
    beds = []
    for seed in (1, 2):
        out = work / f"silo-bed-{seed}"
        result = subprocess.run(
            [solver, str(project / "inputs/accuracy/silo_fill.toml"), "--output-dir", str(out),
             "--set", "insert.0.count=300", "--set", f"simulation.seed={seed}"],
            env=ENV, capture_output=True, text=True)
        if result.returncode != 0:
            failures.append(f"silo bed {seed}: exit {result.returncode}: {result.stderr}")
        beds.append(str(out / "bed.h5"))
    return beds


def check_two_beds(beds):
    command = ["/usr/bin/python3", str(project / "scripts" / "speed_vs_error.py"), "silo",
               "--solver", solver, "--out", str(work / "beds"), "--bed", *beds,
               "--dt-fraction", "0.1", "0.2", "--precision", "double", "--skin", "auto",
               "--integrator", "velocity_verlet", "--step", "auto"]
    result = subprocess.run(command, env=ENV, capture_output=True, text=True)
    if result.returncode != 0 or "[4/4]" not in result.stdout:
        failures.append(f"two-bed silo sweep: exit {result.returncode}: "
                        f"{result.stdout + result.stderr}")
        return
    rows = {row["point"]: row for row in read_table("beds")}
    for name, row in rows.items():
        rates = [json.loads((work / "beds/runs" / f"{name}-b{b}-r1/result.json").read_text())
                 ["observables"]["discharge_rate_per_s"] for b in (1, 2)]
        if row["beds"] != "2" or not math.isclose(float(row["discharge_rate_per_s"]),
                                                  sum(rates) / 2, rel_tol=1e-7):
            failures.append(f"two beds: {name}: beds {row['beds']}, rate "
                            f"{row['discharge_rate_per_s']}, wanted the mean of {rates}")
        spread = float(row["discharge_rate_per_s_error_se"])
        if row["reference"] == "0" and not (math.isfinite(spread) and spread >= 0):
            failures.append(f"two beds: {name}: standard error {spread}")


def observables(rows):
    return [(r["point"], r["repeats"], r["restitution"], r["contact_duration_s"]) for r in rows]


check_pure_functions()
check_bed_means()
beds = silo_beds()
check_two_beds(beds)
code, out = sweep("whole", *GRID, "--repeat", "2")
if code != 0 or "[6/6]" not in out or "within 1 %" not in out:
    failures.append(f"uninterrupted sweep: exit {code}: {out}")
whole = check_table("whole")
check_recommendation("whole", whole)
if not (work / "whole" / "pareto.png").is_file():
    failures.append("no pareto.png")

kill_after("resumed", 2, *GRID, "--repeat", "2")
kept = {p: p.stat().st_mtime_ns for p in (work / "resumed").glob("runs/*/result.json")}
code, out = sweep("resumed", *GRID, "--repeat", "2")
if code != 0 or out.count("done before") != len(kept) or len(kept) < 2:
    failures.append(f"resumed sweep: exit {code}, {len(kept)} runs kept: {out}")
if any(p.stat().st_mtime_ns != t for p, t in kept.items()):
    failures.append("resumed sweep: a finished run was run again")
if observables(check_table("resumed")) != observables(whole):
    failures.append(f"resumed table {observables(read_table('resumed'))} differs from "
                    f"{observables(whole)}")

REFUSED = [
    (["impactt"], "invalid choice: 'impactt'"),
    (["impact", "--dt-fraction"], "argument --dt-fraction: expected at least one argument"),
    (["impact", "--dt-fraction", "0.1", "1.5"], "--dt-fraction 1.5: gpudem-mpi --check refuses"),
    (["impact", "--precision", "double", "quad"], "--precision quad: gpudem-mpi --check refuses"),
    (["impact", "--skin", "auto", "-0.001"], "--skin -0.001: gpudem-mpi --check refuses"),
    (["impact", "--scale", "2"], "--scale: the impact scene keeps its particles"),
    (["impact", "--set", "simulation.dt_fraction=0.3"],
     "--set simulation.dt_fraction: the study sets this key itself"),
    (["silo", "--bed", str(work / "none.h5")], f"--bed: no file {work / 'none.h5'}"),
    (["silo", "--bed", beds[0], beds[0]], "--bed: a bed given twice"),
]
for options, wanted in REFUSED:
    shutil.rmtree(work / "refused", ignore_errors=True)
    command = ["/usr/bin/python3", str(project / "scripts" / "speed_vs_error.py"), *options,
               "--solver", solver, "--out", str(work / "refused")]
    result = subprocess.run(command, env=ENV, capture_output=True, text=True)
    text = result.stdout + result.stderr
    if result.returncode != 2 or wanted not in text or (work / "refused" / "runs").exists():
        failures.append(f"{options}: exit {result.returncode}, '{wanted}' not in {text!r}")

for failure in failures:
    print(failure)
print(f"check_speed_vs_error: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
