#!/usr/bin/python3
"""scripts/calibrate.py on a stand-in solver (fake_calibration_solver.py): the soil's density ρ
(it changes the bed: a bed per density) and friction μ (static and dynamic alike) calibrated to
draft mean 100 ± 5 N, draft spread 15 ± 1 N and bed height 0.09 ± 0.005 m, where the stand-in
gives mean 100 + 0.1 (ρ − 2000) + 200 (μ − 0.5) N, spread 5 + 20 μ N and height
0.1 − 2e-5 (ρ − 1500) m over the window 0.1–0.49 s (40 rows).
- Results: every stored evaluation holds those numbers for its parameters and the objective
  Σ ((simulated − measured)/σ)²; each evaluation number once; its run folder and bed; the plots.
- Kill and resume: Bayesian optimization (batches of 2, 2 runs at once) and differential
  evolution (population 6, 3 at once) killed with SIGKILL while a run hangs, a torn last line
  added to the results file as a kill during a write would leave it, and started again: the
  results equal those of an uninterrupted calibration, and no stored evaluation ran again; the
  first evaluation stored with each bed counts the bed's making time (a bed takes 0.3 s here),
  also for a bed made before the kill. A larger --evaluations extends a finished calibration
  without running the stored ones again.
- Slurm: --slurm with stand-ins for sbatch (runs each array task in turn), srun and squeue gives
  the uninterrupted calibration's evaluations; the array script holds each run.
- Refusals (exit 2, the option or the spec's file, line and key named, nothing run) and a failed
  run (exit 1, naming it; the other evaluation of its batch kept).
- A run stopped as unstable (exit 3) is stored without targets, with the reason and the objective
  of the worst evaluation of its batch or before that ran through, and the calibration goes on;
  killed and resumed, it stores the same evaluations as one never stopped.
- --sensitivity on stored evaluations of known linear targets: the fitted slopes (per unit, on
  a linear and a log scale) within their stated standard deviation, itself under 0.5 %, the
  objective's Gauss–Newton Hessian eigenvalues within 0.1 %, "unique" with two targets and
  "ridge" along the known direction with one; --run-sd sets the fit's least noise, and its
  refusals.
usage: check_calibrate.py PROJECT_SOURCE_DIR WORK_DIR"""
import contextlib
import io
import json
import math
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import time

import numpy as np

project, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
LOG = work / "solver_calls.log"
LOG.touch()
FAKE = project / "tests" / "scripts" / "fake_calibration_solver.py"
MATERIAL = ('[[material]]\nname = "soil"\ndensity = 1850.0\nyoung = 2.0e6\nfriction = 0.7\n'
            'friction_dynamic = 0.6\n\n')
(work / "bed.toml").write_text(
    "[simulation]\nend_time = 1.0\n\n[domain]\nmin = [0, 0, 0]\nmax = [0.2, 0.2, 0.3]\n\n" +
    MATERIAL + "[preparation]\nkinetic_energy = 1e-9\nremove_above = 0.1\n")
(work / "till.toml").write_text(
    "[simulation]\nend_time = 0.6\n\n[domain]\nmin = [0, 0, 0]\nmax = [1, 0.5, 0.5]\n\n" +
    MATERIAL + '[[mesh]]\nname = "sweep"\nfile = "tool.stl"\noffset = [-0.01, 0.25, 0.07]\n\n'
    "[mesh.motion]\ntimes = [0.05, 0.6]\nvelocities = [[0.5, 0, 0], [0.5, 0, 0]]\n\n"
    '[[insert]]\nbed = "elsewhere.h5"\n')
(work / "fixed_bed.h5").write_bytes(b"")
SPEC = ["[calibration]", 'scene = "till.toml"', 'bed_scene = "bed.toml"', 'tool = "sweep"',
        "window = [0.1, 0.49]", "",
        "[[parameter]]", 'name = "density"', 'key = "material.0.density"', "min = 1500.0",
        "max = 2500.0", "bed = true", "",
        "[[parameter]]", 'name = "friction"',
        'key = ["material.0.friction", "material.0.friction_dynamic"]', "min = 0.2",
        "max = 0.8", "",
        "[[target]]", 'quantity = "draft_mean"', "value = 100.0", "sigma = 5.0", "",
        "[[target]]", 'quantity = "draft_std"', "value = 15.0", "sigma = 1.0", "",
        "[[target]]", 'quantity = "bed_height"', "value = 0.09", "sigma = 0.005", ""]
MEASURED = {"draft_mean": (100.0, 5.0), "draft_std": (15.0, 1.0), "bed_height": (0.09, 0.005)}
failures = []


def write_spec(name, lines):
    (work / name).write_text("\n".join(lines) + "\n")
    return str(work / name)


def spec_with(old, new, name="variant.toml"):
    """SPEC with line `old` replaced by `new` (None: removed); (path, 1-based line of it)."""
    index = SPEC.index(old)
    lines = SPEC[:index] + ([] if new is None else [new]) + SPEC[index + 1:]
    return write_spec(name, lines), index + 1


MAIN_SPEC = write_spec("spec.toml", SPEC)


BED_SECONDS = 0.3


def check_bed_times(out):
    """The first evaluation stored with each bed counts the bed's time, as its bed.json says."""
    firsts = {}
    for r in records(out):
        firsts.setdefault(r["bed"], r)
    for bed, r in firsts.items():
        made = json.loads((work / out / bed / "bed.json").read_text()).get("seconds", -1)
        if not (made >= BED_SECONDS and r["wall_s"] >= made):
            failures.append(f"{out}: evaluation {r['evaluation']}, the first with {bed} (made in "
                            f"{made} s), took {r['wall_s']} s without the bed's time")


def calibrate(*options, out="bo", spec=MAIN_SPEC, hang="", fail="", unstable="", wait=True,
              path=None):
    command = ["/usr/bin/python3", str(project / "scripts" / "calibrate.py"), spec,
               "--solver", str(FAKE), "--out", str(work / out), *options]
    env = dict(os.environ, FAKE_SOLVER_LOG=str(LOG), FAKE_SOLVER_HANG=hang,
               FAKE_SOLVER_FAIL=fail, FAKE_SOLVER_UNSTABLE=unstable,
               FAKE_BED_SECONDS=str(BED_SECONDS), OMP_NUM_THREADS="1")
    if path:
        env["PATH"] = f"{path}:{env['PATH']}"
    if not wait:
        return subprocess.Popen(command, env=env, start_new_session=True,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    result = subprocess.run(command, env=env, capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


def calls():
    return LOG.read_text().split()


def records(out):
    lines = (work / out / "evaluations.jsonl").read_text().splitlines()
    return sorted((json.loads(line) for line in lines[1:]), key=lambda r: r["evaluation"])


def comparable(entries):
    keys = ("evaluation", "point", "parameters", "targets", "objective", "run", "bed")
    return [{k: r[k] for k in keys} for r in entries]


def expected_targets(parameters):
    density, friction = parameters["density"], parameters["friction"]
    return {"draft_mean": 100 + 0.1 * (density - 2000) + 200 * (friction - 0.5),
            "draft_std": 5 + 20 * friction, "bed_height": 0.1 - 2e-5 * (density - 1500)}


def check_results(out, count):
    """The results of `out`: `count` evaluations numbered 0.. once each, with the stand-in's
    numbers, their runs and beds, and the outputs."""
    entries = records(out)
    if [r["evaluation"] for r in entries] != list(range(count)):
        failures.append(f"{out}: evaluations {[r['evaluation'] for r in entries]}, wanted "
                        f"0..{count - 1}")
    lines = (work / out / "evaluations.jsonl").read_text().splitlines()[1:]
    in_file_order = [json.loads(line) for line in lines]
    for k, r in enumerate(in_file_order):
        if r["targets"] is None:
            worst = max(s["objective"] for s in in_file_order[:k] if s["targets"] is not None)
            if "unstable at step" not in r.get("unstable", "") or r["objective"] != worst:
                failures.append(f"{out}: evaluation {r['evaluation']} stopped as unstable: "
                                f"stored as {r}, not with the worst objective before it, {worst}")
    for r in entries:
        if r["targets"] is None:
            continue
        low_high = {"density": (1500, 2500), "friction": (0.2, 0.8)}
        for (name, (low, high)), u in zip(low_high.items(), r["point"]):
            if abs(r["parameters"][name] - (low + u * (high - low))) > 1e-9 * high:
                failures.append(f"{out}: evaluation {r['evaluation']}: {name} "
                                f"{r['parameters'][name]} is not at {u} of its range")
        wanted = expected_targets(r["parameters"])
        for quantity, value in wanted.items():
            if abs(r["targets"][quantity] - value) > 1e-9 * max(1, abs(value)):
                failures.append(f"{out}: evaluation {r['evaluation']}: {quantity} "
                                f"{r['targets'][quantity]}, wanted {value}")
        chi2 = sum(((wanted[q] - m) / s) ** 2 for q, (m, s) in MEASURED.items())
        if abs(r["objective"] - chi2) > 1e-9 * max(1, chi2):
            failures.append(f"{out}: evaluation {r['evaluation']}: objective {r['objective']}, "
                            f"wanted {chi2}")
        if r["solver"] != "gpudem-mpi fake" or not r["wall_s"] >= 0 or \
                not (work / out / r["run"] / "timeseries.csv").is_file() or \
                not (work / out / r["bed"] / "bed.h5").is_file():
            failures.append(f"{out}: evaluation {r['evaluation']}: solver, wall time, run or "
                            f"bed missing: {r}")
    best = json.loads((work / out / "best.json").read_text())
    if best["objective"] != min(r["objective"] for r in entries) or best["targets"] is None:
        failures.append(f"{out}: best.json holds objective {best['objective']}, not the least")
    for plot in ("convergence.png", "parameters.png", "best_draft.png"):
        if not (work / out / plot).is_file():
            failures.append(f"{out}: no {plot}")
    return entries


def kill_while_hanging(options, out, run, unstable=""):
    """Starts a calibration and kills it (SIGKILL to it and its runs) once `run` has started."""
    before = len(calls())
    process = calibrate(*options, out=out, hang=run, unstable=unstable, wait=False)
    deadline = time.monotonic() + 60
    while run not in calls()[before:] and time.monotonic() < deadline and process.poll() is None:
        time.sleep(0.05)
    time.sleep(0.3)  # the run beside it in its batch finishes
    os.killpg(process.pid, signal.SIGKILL)
    process.wait()


def check_resume(options, out, run, count, unstable=""):
    """A calibration killed at `run` and resumed equals the uninterrupted one in out + "-whole"."""
    code, text = calibrate(*options, out=out + "-whole", unstable=unstable)
    if code != 0:
        failures.append(f"{out}-whole: exit {code}: {text}")
        return
    whole = check_results(out + "-whole", count)
    kill_while_hanging(options, out, run, unstable)
    stored = {f"e{r['evaluation']:05d}" for r in records(out)}
    with open(work / out / "evaluations.jsonl", "a") as results:
        results.write('{"evaluation": 99, "point": [0.5')  # a write cut short
    before = len(calls())
    code, text = calibrate(*options, out=out, unstable=unstable)
    rerun = stored & set(calls()[before:])
    if code != 0 or comparable(check_results(out, count)) != comparable(whole) or rerun:
        failures.append(f"{out}: resumed (exit {code}) unlike the uninterrupted calibration, or "
                        f"ran stored evaluations {sorted(rerun)} again: {text}")
    if "found in evaluations.jsonl" not in text or f"[{count}/{count}]" not in text:
        failures.append(f"{out}: progress lines missing: {text!r}")
    check_bed_times(out)


BO = ["--optimizer", "bo", "--evaluations", "10", "--batch", "2", "--jobs", "2"]
DE = ["--optimizer", "de", "--population", "6", "--evaluations", "18", "--jobs", "3"]
check_resume(BO, "bo", "e00007", 10)
check_resume(DE, "de", "e00008", 12 + 6)
check_resume(BO, "bo-unstable", "e00007", 10, unstable="e00003")
if [r["evaluation"] for r in records("bo-unstable") if r["targets"] is None] != [3]:
    failures.append("bo-unstable: evaluation 3, stopped as unstable, is not the one stored so")

before = len(calls())
code, text = calibrate(*BO[:2], "--evaluations", "14", *BO[4:], out="bo-whole")
passes = sorted(name for name in calls()[before:] if name.startswith("e"))
if code != 0 or comparable(records("bo-whole")[:10]) != comparable(records("bo")) or \
        passes != [f"e{n:05d}" for n in range(10, 14)]:
    failures.append(f"extended to 14: exit {code}, solver calls {calls()[before:]}: {text}")

# Slurm: stand-ins that run every array task at once (sbatch), a task's command (srun) and an
# empty queue (squeue).
bin_dir = work / "bin"
bin_dir.mkdir()
(bin_dir / "sbatch").write_text(
    '#!/usr/bin/env bash\necho "$@" >> "$(dirname "$0")/sbatch.log"\nscript="${@: -1}"\n'
    'last=$(sed -n "s/^#SBATCH --array=0-\\([0-9]*\\).*/\\1/p" "$script")\n'
    'for ((i = 0; i <= last; ++i)); do SLURM_ARRAY_TASK_ID=$i bash "$script"; done\n'
    "echo 4242\n")
(bin_dir / "srun").write_text('#!/usr/bin/env bash\nwhile [[ $1 == --* ]]; do shift; done\n'
                              'exec "$@"\n')
(bin_dir / "squeue").write_text("#!/usr/bin/env bash\nexit 0\n")
for tool in ("sbatch", "srun", "squeue"):
    (bin_dir / tool).chmod(0o755)
code, text = calibrate("--optimizer", "bo", "--evaluations", "6", "--batch", "2", "--slurm",
                       "--poll", "0.05", "--sbatch-args", "--account=p1 --time=1:00:00",
                       out="slurm", path=bin_dir)
if code != 0 or comparable(records("slurm")) != comparable(records("bo")[:6]):
    failures.append(f"--slurm: exit {code}, results unlike the local run's: {text}")
scripts = sorted((work / "slurm" / "slurm").glob("*.sbatch"))
first = scripts[0].read_text() if scripts else ""
for wanted in ("#SBATCH --array=0-5", "#SBATCH --ntasks=1", str(FAKE), "exit_code",
               str(work / "slurm" / "beds"), 'srun --cpus-per-task="$OMP_NUM_THREADS"'):
    if wanted not in first:
        failures.append(f"--slurm: '{wanted}' not in the first array script {first!r}")
sbatch_log = (bin_dir / "sbatch.log").read_text() if (bin_dir / "sbatch.log").is_file() else ""
if "--parsable --account=p1 --time=1:00:00" not in sbatch_log or len(scripts) != 2:
    failures.append(f"--slurm: {len(scripts)} array scripts (wanted 2: the six beds and the six "
                    f"runs of the starting batch), sbatch called with {sbatch_log!r}")

# Refusals: exit 2, the message, and no run.
inverted, inverted_line = spec_with("max = 2500.0", "max = 1400.0", "inverted.toml")
empty, empty_line = spec_with("max = 0.8", "max = 0.2", "empty.toml")
log_zero, log_line = spec_with("min = 0.2", "min = 0.0\nlog = true", "log.toml")
unknown, unknown_line = spec_with("min = 0.2", "mni = 0.2", "unknown.toml")
quantity, quantity_line = spec_with('quantity = "draft_std"', 'quantity = "draft_max"', "q.toml")
no_bed_scene, no_bed_line = spec_with('bed_scene = "bed.toml"', 'bed = "fixed_bed.h5"',
                                      "fixed.toml")
no_tool, tool_line = spec_with('tool = "sweep"', 'tool = "plough"', "tool.toml")
bad_key, bad_key_line = spec_with('key = "material.0.density"', 'key = "material.0.densty"',
                                  "key.toml")
own_key, own_line = spec_with('key = "material.0.density"', 'key = "simulation.end_time"',
                              "own.toml")
no_scene, scene_line = spec_with('scene = "till.toml"', 'scene = "none.toml"', "scene.toml")
no_bed, bed_line = spec_with('bed_scene = "bed.toml"', 'bed = "none.h5"', "bed.toml.spec")
REFUSED = [
    ([], "--evaluatons", "unrecognized arguments: --evaluatons"),
    ([], "--optimizer de --population 6 --evaluations 5",
     "--evaluations 5: less than one generation of --population 6"),
    ([], "--solver /nonexistent/gpudem-mpi", "--solver: no executable file /nonexistent"),
    ([], "--seed 2 --evaluations 10 --batch 2 --out " + str(work / "bo"),
     "--seed 2: " + str(work / "bo" / "evaluations.jsonl") + " holds a calibration with --seed 1"),
    ([inverted], "", f"inverted.toml:{inverted_line}: parameter.0.max: empty or inverted bounds"),
    ([empty], "", f"empty.toml:{empty_line}: parameter.1.max: empty or inverted bounds"),
    ([log_zero], "", f"log.toml:{log_line}: parameter.1.min: a log scale needs min > 0"),
    ([unknown], "", f"unknown.toml:{unknown_line}: parameter.1.mni: unknown key"),
    ([quantity], "", f"q.toml:{quantity_line}: target.1.quantity: 'draft_max' is none of"),
    ([no_bed_scene], "", f"fixed.toml:{SPEC.index('bed = true') + 1}: parameter.0.bed: bed = "
                         "true needs calibration.bed_scene"),
    ([no_tool], "", f"tool.toml:{tool_line}: calibration.tool: a draft target needs the moving"),
    ([bad_key], "", f"key.toml:{bad_key_line}: parameter.0.key: at 1500: gpudem-mpi --check "
                    "refuses it: gpudem-mpi: error:"),
    ([own_key], "", f"own.toml:{own_line}: parameter.0.key: simulation.end_time: the "
                    "calibration sets it itself"),
    ([no_scene], "", f"scene.toml:{scene_line}: calibration.scene: no file"),
    ([no_bed], "", f"bed.toml.spec:{bed_line}: calibration.bed: no file"),
]
sys.path.insert(0, str(project / "scripts"))
import calibrate as calibrate_module  # noqa: E402

os.environ.update(FAKE_SOLVER_LOG=str(LOG), OMP_NUM_THREADS="1")


def calibrate_here(*options, out="refused", spec=MAIN_SPEC):
    """calibrate.py's main in this process (no start-up time): (exit code, output)."""
    text = io.StringIO()
    with contextlib.redirect_stdout(text), contextlib.redirect_stderr(text):
        try:
            code = calibrate_module.main([spec, "--solver", str(FAKE), "--out", str(work / out),
                                          *options])
        except SystemExit as error:
            code = error.code
    return code, text.getvalue()


code, text = calibrate(out="refused", spec=inverted)
if code != 2 or "parameter.0.max: empty or inverted bounds" not in text:
    failures.append(f"inverted bounds: exit {code} from the command: {text!r}")
for spec, options, wanted in REFUSED:
    before = len(calls())
    code, text = calibrate_here(*options.split(), spec=(spec or [MAIN_SPEC])[0])
    if code != 2 or wanted not in text or len(calls()) != before:
        failures.append(f"{spec} {options}: exit {code}, {len(calls()) - before} runs, "
                        f"'{wanted}' not in {text!r}")
fixed_no_height = write_spec("fixed_height.toml", [
    line.replace('bed_scene = "bed.toml"', 'bed = "fixed_bed.h5"').replace("bed = true",
                                                                          "bed = false")
    for line in SPEC])
code, text = calibrate_here(spec=fixed_no_height)
height_line = SPEC.index('quantity = "bed_height"') + 1
if code != 2 or f"fixed_height.toml:{height_line}: target.2.quantity: bed_height is measured " \
        "on the bed the calibration makes" not in text:
    failures.append(f"bed_height without a bed scene: exit {code}: {text!r}")
code, text = calibrate_here("--check", out="checked")
if code != 0 or "valid" not in text or (work / "checked").exists():
    failures.append(f"--check: exit {code}, or it wrote {work / 'checked'}: {text}")

code, text = calibrate(*BO, out="failing", fail="e00003")
if code != 1 or "e00003 failed (exit 1)" not in text or "a failure made on purpose" not in text \
        or [r["evaluation"] for r in records("failing")] != [0, 1, 2, 4, 5]:
    failures.append(f"a failed run: exit {code}, stored "
                    f"{[r['evaluation'] for r in records('failing')]}: {text!r}")


# --sensitivity on synthetic evaluations around u* = (0.5, 0.5), z = u − u*: draft mean
# 100 + 60 z1 − 17 z2 N, spread 15 + 10 z2 N (15 N in the ridge case), bed height 0.09 m; the
# friction on a log scale from 0.2 to 0.8 (0.4 at u*).
def synthetic(out, spread_slope):
    (work / out).mkdir()
    lines = [json.dumps({"calibration": {"synthetic": True}})]
    steps = 0.5 + 0.0625 * np.arange(-3, 4)
    grid = [(a, b) for a in steps for b in steps]
    for number, (u1, u2) in enumerate(grid):
        z1, z2 = u1 - 0.5, u2 - 0.5
        targets = {"draft_mean": 100 + 60 * z1 - 17 * z2, "draft_std": 15 + spread_slope * z2,
                   "bed_height": 0.09}
        lines.append(json.dumps({
            "evaluation": number, "point": [u1, u2],
            "parameters": {"density": 1500 + 1000 * u1, "friction": 0.2 * 4 ** u2},
            "targets": targets, "objective": sum(((targets[q] - m) / s) ** 2
                                                 for q, (m, s) in MEASURED.items())}))
    (work / out / "evaluations.jsonl").write_text("\n".join(lines) + "\n")
    code, text = calibrate_here("--sensitivity", out=out, spec=log_spec)
    result = json.loads((work / out / "sensitivity.json").read_text()) if code == 0 else {}
    return code, text, result


log_spec = write_spec("log_friction.toml",
                      [line.replace("max = 0.8", "max = 0.8\nlog = true") for line in SPEC])
jacobian = np.array([[60 / 5, -17 / 5], [0, 10 / 1]])
for out, slope, verdict in (("unique", 10, "unique"), ("ridge", 0, "ridge")):
    code, text, result = synthetic(out, slope)
    rows = jacobian if slope else jacobian[:1]
    eigenvalues = np.linalg.eigvalsh(2 * rows.T @ rows)
    got = result.get("hessian_eigenvalues", [])
    if code != 0 or result.get("optimum") != verdict or len(got) != 2 or \
            np.abs(np.array(got) - eigenvalues).max() > 1e-3 * eigenvalues.max():
        failures.append(f"--sensitivity {out}: exit {code}, {result.get('optimum')} with "
                        f"eigenvalues {got}, wanted {verdict} with {eigenvalues}: {text}")
        continue
    mean = result["targets"]["draft_mean"]["slopes"]
    wanted = {("density", "per_unit"): 60 / 1000, ("density", "per_range"): 60,
              ("friction", "per_range"): -17,
              ("friction", "per_unit"): -17 / (math.log(4) * 0.4)}
    for (name, kind), value in wanted.items():  # within its stated sd, itself under 0.5 %
        got, sd = mean[name][kind], mean[name][kind + "_sd"]
        if abs(got - value) > 2 * sd or sd > 5e-3 * abs(value):
            failures.append(f"--sensitivity {out}: d draft_mean / d {name} {kind} "
                            f"{got} ± {sd}, wanted {value}")
    if {"unique": "the optimum is unique", "ridge": "the optimum is a ridge"}[verdict] not in text:
        failures.append(f"--sensitivity {out}: no verdict line in {text!r}")
    if verdict == "ridge":
        direction = np.array(list(result["flat_directions"][0]["direction"].values()))
        if len(result["flat_directions"]) != 1 or \
                abs(abs(direction @ np.array([3.4, 12]) / math.hypot(3.4, 12)) - 1) > 1e-3:
            failures.append(f"--sensitivity ridge: flat directions {result['flat_directions']}, "
                            "wanted one along (3.4, 12)")
# --run-sd: the fit of noise-free values takes the least noise allowed, the given spread, and
# its slopes stay within their (wider) standard deviation; refusals name the option.
code, text = calibrate_here("--sensitivity", "--run-sd", "draft_mean=2", out="unique",
                            spec=log_spec)
fit = json.loads((work / "unique" / "sensitivity.json").read_text())["targets"]["draft_mean"] \
    if code == 0 else {}
if code != 0 or abs(fit["noise_sd"] - 2) > 1e-6 or "scatter by 2 N" not in text or \
        abs(fit["slopes"]["density"]["per_range"] - 60) > 3 * fit["slopes"]["density"][
            "per_range_sd"]:
    failures.append(f"--sensitivity --run-sd draft_mean=2: exit {code}, {fit}: {text}")
for options, message in ((["--sensitivity", "--run-sd", "repose=1"],
                          "--run-sd repose=1: repose is not a target of the spec"),
                         (["--sensitivity", "--run-sd", "draft_mean=-1"],
                          "--run-sd draft_mean=-1: SD takes a value > 0"),
                         (["--check", "--run-sd", "draft_mean=1"],
                          "--run-sd goes with --sensitivity")):
    code, text = calibrate_here(*options, out="unique", spec=log_spec)
    if code != 2 or message not in text:
        failures.append(f"{options}: exit {code}: {text!r}")
code, text = calibrate_here("--sensitivity", out="nothing")
if code != 2 or "--sensitivity: a Gaussian process in 2 parameters needs at least 6 " \
        "evaluations that ran through; there are 0" not in text:
    failures.append(f"--sensitivity without evaluations: exit {code}: {text!r}")

for failure in failures:
    print(failure)
print(f"check_calibrate: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
