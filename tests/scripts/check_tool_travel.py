#!/usr/bin/env python3
"""The steady-window rule of scripts/tool_travel.py on synthetic motions, the times worked out by
hand (to 1e-6 s: a binary STL holds float32). The tool is one triangle 0.2 m long behind its
nose (the origin, pointing along +x).
- Along +x, unturned, front at x = −0.05 in the bin x = 0..1, 0.5 m/s from t = 0.1 s: the whole
  tool is in the bed after 0.25 m, at t = 0.1 + 0.25/0.5 = 0.6 s; its front is 0.2 m before the
  far face after 0.85 m, at t = 0.1 + 0.85/0.5 = 1.8 s; the run's end (1.5 s) or the last
  keyframe (1.0 s) cuts the window short; a run that ends at 0.5 s has none.
- Along −x, turned by 180° (rotation_degrees, or rotation_angle = π; an ASCII STL), front at
  x = 1.25 in the bin x = 0..1.2, speeding up from 0 at t = 0.2 s to 1 m/s at 0.6 s (0.2 m):
  in the bed after 1.25 − 1.2 + 0.2 = 0.25 m, at t = 0.6 + 0.05/1 = 0.65 s; 0.2 m before the far
  face (x = 0.2) after 1.05 m, at t = 0.6 + 0.85 = 1.45 s. With an entry length of 0.1 m, 0.15 m
  into the ramp: ½·2.5·τ² = 0.15, t = 0.2 + √0.12 = 0.5464 s; with a margin of 0.5 m, after
  0.75 m, at t = 1.15 s.
- Along +y, turned by +90° about z (its nose then points along +y, its wings along −y), front
  at y = −0.05 in the bin y = 0..0.5, 0.5 m/s from t = 0.1 s: in the bed at 0.6 s as along +x,
  0.2 m before the far face after 0.35 m, at t = 0.8 s.
- A tool moving against its travel part of the time, or one that never reaches the bed, is
  refused.
usage: check_tool_travel.py PROJECT_SOURCE_DIR WORK_DIR"""
import math
import pathlib
import shutil
import sys

project, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
sys.path.insert(0, str(project / "scripts"))
from stl_file import write_binary_stl  # noqa: E402
from tool_travel import SceneError, find_tool, steady_window, time_at_travel  # noqa: E402

shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)
TRIANGLE = ((0, 0, 0), (-0.2, 0.05, 0), (-0.2, -0.05, 0.1))
write_binary_stl(work / "tool.stl", "tool", [TRIANGLE])
(work / "tool_ascii.stl").write_text(
    "solid tool\nfacet normal 0 0 1\nouter loop\n" +
    "".join(f"vertex {x} {y} {z}\n" for x, y, z in TRIANGLE) + "endloop\nendfacet\nendsolid\n")
failures = []


def scene(bin_length, mesh):
    return {"domain": {"min": [0, 0, 0], "max": [bin_length, 0.5, 0.5]}, "mesh": [mesh]}


def tool(mesh_keys, times, velocities):
    mesh = {"name": "tool", "file": "tool.stl", "offset": [-0.05, 0.25, 0.1], **mesh_keys,
            "motion": {"times": times, "velocities": velocities}}
    return mesh


def expect(what, bin_length, mesh, run_end, wanted, **rule):
    s = scene(bin_length, mesh)
    try:
        got = steady_window(find_tool(s, work / "till.toml", "tool"), s, run_end, **rule)
    except SceneError as error:
        got = f"refused: {error}"
    if isinstance(wanted, str):
        ok = isinstance(got, str) and wanted in got
    else:
        ok = not isinstance(got, str) and all(abs(g - w) < 1e-6 for g, w in zip(got, wanted))
    if not ok:
        failures.append(f"{what}: got {got}, wanted {wanted}")


forward = tool({}, [0.1, 2.1], [[0.5, 0, 0], [0.5, 0, 0]])
expect("+x", 1.0, forward, 3.0, (0.6, 1.8))
expect("+x, run ends at 1.5 s", 1.0, forward, 1.5, (0.6, 1.5))
expect("+x, motion ends at 1 s", 1.0, tool({}, [0.1, 1.0], [[0.5, 0, 0]] * 2), 3.0, (0.6, 1.0))
expect("+x, run ends at 0.5 s", 1.0, forward, 0.5, "no steady window for mesh 'tool'")

ramp = ([0.2, 0.6, 3.0], [[0, 0, 0], [-1, 0, 0], [-1, 0, 0]])
for turn in ({"rotation_degrees": 180}, {"rotation_angle": math.pi, "file": "tool_ascii.stl"}):
    backward = tool({"offset": [1.25, 0.25, 0.1], **turn}, *ramp)
    expect(f"−x, {turn}", 1.2, backward, 3.0, (0.65, 1.45))
    expect(f"−x, {turn}, entry 0.1 m, margin 0.5 m", 1.2, backward, 3.0,
           (0.2 + math.sqrt(0.12), 1.15), entry=0.1, margin=0.5)

sideways = tool({"offset": [0.5, -0.05, 0.1], "rotation_degrees": 90}, [0.1, 2.1],
                [[0, 0.5, 0], [0, 0.5, 0]])
expect("+y, turned by 90°", 1.0, sideways, 3.0, (0.6, 0.8))

there_and_back = tool({}, [0.1, 1.0, 2.0], [[0.5, 0, 0], [0.5, 0, 0], [-0.5, 0, 0]])
expect("back and forth", 1.0, there_and_back, 3.0, "moves against its travel")
if time_at_travel([0.1, 1.0], [0.5, 0.5], 0.46) is not None:
    failures.append("0.46 m travelled by a tool that moves 0.45 m")

for failure in failures:
    print(failure)
print(f"check_tool_travel: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
