#!/usr/bin/python3
"""A stand-in for gpudem-mpi in check_calibrate.py. Takes a scene, --output-dir and --set options
(a value in TOML), --check and --version.
--check: exit 2 naming the key when a --set key is not in the scene (a dotted path of tables and
0-based array indices; the last part may be new only when the scene has no such key, as the
real solver's unknown-key check does for its known keys, here the scene's own) or when a bed
source names no file; else exit 0.
A bed scene (one with [preparation]) writes preparation.bed_file: a 10 × 10 square grid of
spheres of radius 0.01 m whose tops are at h = 0.1 − 2e-5 (ρ − 1500) m, ρ = material.0.density.
A pass writes OUTPUT_DIR/timeseries.csv, a row every 0.01 s up to simulation.end_time, of the
force on the mesh "sweep" travelling along +x: draft m + s (−1)^k on row k, so that over an even
number of rows its mean is m = 100 + 0.1 (ρ − 2000) + 200 (μ − 0.5) N and its (population)
standard deviation s = 5 + 20 μ N, μ = material.0.friction.
Appends the output folder's name to $FAKE_SOLVER_LOG for each run (not for --check); sleeps when
that name is $FAKE_SOLVER_HANG (to be killed), fails with exit 1 when it is $FAKE_SOLVER_FAIL
and stops as unstable (exit 3, as gpudem-mpi does) when it is $FAKE_SOLVER_UNSTABLE. A bed
takes $FAKE_BED_SECONDS (default 0) to make."""
import os
import pathlib
import sys
import time
import tomllib

args = sys.argv[1:]
if args == ["--version"]:
    print("gpudem-mpi fake")
    sys.exit(0)
scene_path = pathlib.Path(args[0])
scene = tomllib.loads(scene_path.read_text())
settings = {}
for i, word in enumerate(args):
    if word == "--set":
        key, _, value = args[i + 1].partition("=")
        settings[key] = tomllib.loads(f"v = {value}")["v"]


def lookup(key):
    """The scene's table holding `key`'s last part, or None when a part before it is missing."""
    node = scene
    for part in key.split(".")[:-1]:
        node = node[int(part)] if isinstance(node, list) and part.isdigit() else \
            node.get(part) if isinstance(node, dict) else None
        if node is None:
            return None
    return node


def setting(key, default):
    return settings.get(key, default)


if "--check" in args:
    for key in settings:
        table, last = lookup(key), key.split(".")[-1]
        known = isinstance(table, list) and last.isdigit() or \
            isinstance(table, dict) and last in table
        if not known:
            print(f"gpudem-mpi: error: {scene_path}: key '{key}': unknown key")
            sys.exit(2)
    for index, source in enumerate(scene.get("insert", [])):
        bed = settings.get(f"insert.{index}.bed", source.get("bed"))
        if isinstance(settings.get(f"insert.{index}"), dict):
            bed = settings[f"insert.{index}"].get("bed")
        if bed is not None and not (scene_path.parent / bed).is_file():
            print(f"gpudem-mpi: error: {scene_path}: cannot read the bed {bed}")
            sys.exit(2)
    print("scene is valid")
    sys.exit(0)

out = pathlib.Path(args[args.index("--output-dir") + 1])
with open(os.environ["FAKE_SOLVER_LOG"], "a") as log:
    log.write(out.name + "\n")
if out.name == os.environ.get("FAKE_SOLVER_HANG"):
    time.sleep(120)
if out.name == os.environ.get("FAKE_SOLVER_FAIL"):
    print("gpudem-mpi: error: a failure made on purpose")
    sys.exit(1)
if out.name == os.environ.get("FAKE_SOLVER_UNSTABLE"):
    print("gpudem-mpi: error: unstable at step 7 (made on purpose)")
    sys.exit(3)

density = setting("material.0.density", scene["material"][0]["density"])
friction = setting("material.0.friction", scene["material"][0]["friction"])
out.mkdir(parents=True, exist_ok=True)
if "preparation" in scene:
    import h5py
    time.sleep(float(os.environ.get("FAKE_BED_SECONDS", "0")))
    height = 0.1 - 2e-5 * (density - 1500)
    with h5py.File(setting("preparation.bed_file", "bed.h5"), "w") as bed:
        bed["position_radius"] = [[0.02 * i + 0.01, 0.02 * j + 0.01, height - 0.01, 0.01]
                                  for i in range(10) for j in range(10)]
    sys.exit(0)
mean = 100 + 0.1 * (density - 2000) + 200 * (friction - 0.5)
spread = 5 + 20 * friction
rows = ["time,step,sweep_fx,sweep_fy,sweep_fz"]
for step in range(round(setting("simulation.end_time", scene["simulation"]["end_time"]) / 0.01)
                  + 1):
    rows.append(f"{round(step * 0.01, 10)},{step},{-(mean + spread * (-1) ** step)},0,0")
(out / "timeseries.csv").write_text("\n".join(rows) + "\n")
