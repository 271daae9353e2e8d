#!/usr/bin/python3
"""A stand-in for gpudem-mpi in check_tillage_study.py: takes a scene and the study's --output-dir
and --set options, and writes OUTPUT_DIR/timeseries.csv, a row every 0.003 s up to
simulation.end_time, of the force on the mesh "sweep" travelling along +x. With depth
D = 0.15 − (mesh.0.offset)_z, speed V = (mesh.0.motion.velocities)[0]_x and density factor
ρ = material.0.density / 1000 (1 without it), the force is draft 1000 D + 50 V, vertical −400 D
and lateral 10 V, times ρ, all times min(1, max(0, x / 0.2)) with x = −0.01 + V (t − t0) the
tool's nose, t0 the scene's first keyframe: it grows while the tool (0.2 m long) enters the bed
at x = 0, and is steady once the tool is wholly in.
Appends the output folder's name to $FAKE_GPUDEM_LOG; sleeps when that name is
$FAKE_GPUDEM_HANG (to be killed) and fails with exit 3 when it is $FAKE_GPUDEM_FAIL."""
import os
import pathlib
import sys
import time
import tomllib

args = sys.argv[1:]
out = pathlib.Path(args[args.index("--output-dir") + 1])
settings = {}
for i, word in enumerate(args):
    if word == "--set":
        key, _, value = args[i + 1].partition("=")
        settings[key] = tomllib.loads(f"v = {value}")["v"]
with open(os.environ["FAKE_GPUDEM_LOG"], "a") as log:
    log.write(out.name + "\n")
if out.name == os.environ.get("FAKE_GPUDEM_HANG"):
    time.sleep(60)
if out.name == os.environ.get("FAKE_GPUDEM_FAIL"):
    print("gpudem-mpi: error: a failure made on purpose")
    sys.exit(3)

with open(args[0], "rb") as f:
    start = tomllib.load(f)["mesh"][0]["motion"]["times"][0]
depth = 0.15 - settings["mesh.0.offset"][2]
speed = settings["mesh.0.motion.velocities"][0][0]
density = settings.get("material.0.density", 1000) / 1000
rows = ["time,step,sweep_fx,sweep_fy,sweep_fz"]
for step in range(int(settings["simulation.end_time"] / 0.003) + 1):
    t = step * 0.003
    inside = min(1.0, max(0.0, (-0.01 + speed * max(0.0, t - start)) / 0.2)) * density
    rows.append(f"{t},{step},{-(1000 * depth + 50 * speed) * inside},{10 * speed * inside},"
                f"{-400 * depth * inside}")
out.mkdir(parents=True, exist_ok=True)
(out / "timeseries.csv").write_text("\n".join(rows) + "\n")
