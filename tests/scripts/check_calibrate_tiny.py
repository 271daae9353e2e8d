#!/usr/bin/python3
"""scripts/calibrate.py end to end with gpudem-mpi on the tiny case (inputs/calibration/tiny.toml:
about 530 spheres, the soil's density changes the bed, its friction the pass; targets draft mean
and bed height). Three evaluations by Bayesian optimization (a start of two, run at once, and one
proposal), then the same command with --evaluations 4: the three are kept and not run again, one
more runs. Each stored evaluation: parameters within their bounds, the draft mean equal to the
mean of −sweep_fx over its run's rows in the window of the sweep's pass (0.4 × 0.245 m long,
its nose at x = −0.005 m, 0.5 m/s from t = 0.02 s: from its whole length in the bed at 0.226 s
to the run's end at 0.4 s), a bed height between the trim height 0.07 m and 0.07 m plus the
largest radius, and the objective Σ ((simulated − measured)/σ)² of those. Refused with exit 2
before any run: a key gpudem-mpi does not know and a bound outside what it accepts (both found by
gpudem-mpi --check), and a missing solver.
usage: check_calibrate_tiny.py PROJECT_SOURCE_DIR GPUDEM_MPI WORK_DIR"""
import csv
import json
import os
import pathlib
import shutil
import subprocess
import sys

project, solver, work = (pathlib.Path(a).resolve() for a in sys.argv[1:4])
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
SPEC = project / "inputs" / "calibration" / "tiny.toml"
MEASURED = {"draft_mean": (12.0, 2.0), "bed_height": (0.075, 0.005)}
BOUNDS = {"density": (1500.0, 2500.0), "friction": (0.3, 0.8)}
WINDOW = (0.226, 0.4)
failures = []


def calibrate(*options, spec=SPEC, out="run", solver_path=solver):
    command = ["/usr/bin/python3", str(project / "scripts" / "calibrate.py"), str(spec),
               "--solver", str(solver_path), "--out", str(work / out), "--initial", "2",
               "--batch", "1", "--jobs", "2", *options]
    result = subprocess.run(command, capture_output=True, text=True,
                            env=dict(os.environ, OMP_NUM_THREADS="1"))
    return result.returncode, result.stdout + result.stderr


def records():
    lines = (work / "run" / "evaluations.jsonl").read_text().splitlines()
    return sorted((json.loads(line) for line in lines[1:]), key=lambda r: r["evaluation"])


def window_draft(run):
    with open(work / "run" / run / "timeseries.csv", newline="") as f:
        steady = [-float(row["sweep_fx"]) for row in csv.DictReader(f)
                  if WINDOW[0] - 1e-6 <= float(row["time"]) <= WINDOW[1] + 1e-6]
    return sum(steady) / len(steady), len(steady)


def check(entry):
    name = f"evaluation {entry['evaluation']}"
    for parameter, (low, high) in BOUNDS.items():
        if not low <= entry["parameters"][parameter] <= high:
            failures.append(f"{name}: {parameter} {entry['parameters'][parameter]} outside "
                            f"{low}..{high}")
    mean, rows = window_draft(entry["run"])
    if rows < 80 or abs(entry["targets"]["draft_mean"] - mean) > 1e-9 * max(1.0, abs(mean)):
        failures.append(f"{name}: draft mean {entry['targets']['draft_mean']}, wanted {mean} "
                        f"over {rows} rows")
    if not 0.07 <= entry["targets"]["bed_height"] <= 0.081:
        failures.append(f"{name}: bed height {entry['targets']['bed_height']} m")
    chi2 = sum(((entry["targets"][q] - m) / s) ** 2 for q, (m, s) in MEASURED.items())
    if abs(entry["objective"] - chi2) > 1e-9 * max(1.0, chi2) or \
            not entry["solver"].startswith("gpudem-mpi ") or \
            not (work / "run" / entry["bed"] / "bed.h5").is_file():
        failures.append(f"{name}: objective {entry['objective']} (wanted {chi2}), solver "
                        f"{entry['solver']} or bed {entry['bed']}")


code, out = calibrate("--evaluations", "3")
first = records() if code == 0 else []
if code != 0 or [r["evaluation"] for r in first] != [0, 1, 2] or "[3/3]" not in out:
    failures.append(f"first calibration: exit {code}: {out}")
for entry in first:
    check(entry)
stamps = {r["run"]: (work / "run" / r["run"] / "timeseries.csv").stat().st_mtime_ns
          for r in first}

code, out = calibrate("--evaluations", "4")
second = records() if code == 0 else []
if code != 0 or second[:3] != first or [r["evaluation"] for r in second] != [0, 1, 2, 3] or \
        "found in evaluations.jsonl" not in out:
    failures.append(f"resumed to 4 evaluations: exit {code}: {out}")
if any((work / "run" / run / "timeseries.csv").stat().st_mtime_ns != stamp
       for run, stamp in stamps.items()):
    failures.append("resumed: a stored evaluation ran again")
for entry in second[3:]:
    check(entry)
for plot in ("convergence.png", "parameters.png", "best_draft.png", "best.json"):
    if not (work / "run" / plot).is_file():
        failures.append(f"no {plot}")

text = SPEC.read_text().replace('"tiny_till.toml"', f'"{SPEC.parent / "tiny_till.toml"}"') \
    .replace('"tiny_bed.toml"', f'"{SPEC.parent / "tiny_bed.toml"}"')
variants = {"unknown_key.toml": ('key = "material.0.density"', 'key = "material.0.densty"'),
            "bound.toml": ("max = 0.8", "max = 1.2\n[[parameter]]\nkey = \"material.0.poisson\""
                           "\nmin = 0.3\nmax = 0.6")}
key_line = text.splitlines().index(variants["unknown_key.toml"][0]) + 1
REFUSED = [
    ("unknown_key.toml", f"unknown_key.toml:{key_line}: parameter.0.key: at 1500: gpudem-mpi "
     "--check refuses it:", "unknown key 'densty'"),
    ("bound.toml", "parameter.2.key: at 0.6: gpudem-mpi --check refuses it:",
     "material[0].poisson"),
]
for name, (old, new) in variants.items():
    (work / name).write_text(text.replace(old, new))
for name, wanted, detail in REFUSED:
    code, out = calibrate(spec=work / name, out="refused")
    if code != 2 or wanted not in out or detail not in out or (work / "refused").exists():
        failures.append(f"{name}: exit {code}, '{wanted}' or '{detail}' not in {out!r}")
code, out = calibrate(out="refused", solver_path=work / "none")
if code != 2 or f"--solver: no executable file {work / 'none'}" not in out:
    failures.append(f"a missing solver: exit {code}: {out!r}")

for failure in failures:
    print(failure)
print(f"check_calibrate_tiny: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
