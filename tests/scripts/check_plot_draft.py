#!/usr/bin/env python3
"""scripts/plot_draft.py on a synthetic time series: a tool travelling along −x (from its scene's
motion, or --axis -x) whose soil pushes it along +x by 50 N, up by 20 N and along +y by 5 N has
draft 50 N, vertical 20 N and lateral −5 N (left of a travel along −x is −y), over the steady
window only: given by --steady 0.5 1, or without it taken from the scene's motion (the tool, 0.07 m
long, its front at x = 1.2 at 0.7 m/s from t = 0.1 s in the bin x = 0..1, is its own length in
the bed after 0.27 m, at t = 0.1 + 0.27/0.7 = 0.486 s; it would be 0.07 m before the far face
at t = 1.729 s, after the last row, t = 1 s); the plot is written; a tool that does not move, a
missing column, or a pass that never enters the bed in the run, is refused.
usage: check_plot_draft.py PROJECT_SOURCE_DIR WORK_DIR"""
import pathlib
import shutil
import subprocess
import sys

project, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
script = project / "scripts" / "plot_draft.py"
shutil.rmtree(work, ignore_errors=True)
work.mkdir(parents=True)

rows = ["time,step,tine_fx,tine_fy,tine_fz,still_fx,still_fy,still_fz"]
for k in range(11):  # t = 0 .. 1 s; the forces of the first half are not steady
    t = k / 10
    scale = 1.0 if t >= 0.5 else 9.0
    rows.append(f"{t},{k},{50 * scale},{5 * scale},{20 * scale},0,0,0")
(work / "ts.csv").write_text("\n".join(rows) + "\n")
(work / "tine.stl").write_text(  # nose at the origin, 0.07 m long behind it along +x
    "solid tine\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.07 0 0\n"
    "vertex 0.07 0.01 0.01\nendloop\nendfacet\nendsolid tine\n")
(work / "till.toml").write_text(
    '[domain]\nmin = [0, 0, 0]\nmax = [1, 0.5, 0.5]\n\n[[mesh]]\nname = "tine"\n'
    'file = "tine.stl"\noffset = [1.2, 0.25, 0.1]\n\n[mesh.motion]\ntimes = [0.1, 2]\n'
    'velocities = [[-0.7, 0, 0], [-0.7, 0, 0]]\n\n[[mesh]]\nname = "still"\nfile = "x.stl"\n')

failures = []


def run(*args):
    result = subprocess.run(["/usr/bin/python3", str(script), str(work / "ts.csv"),
                             str(work / "out.png"), "--tool", "tine", *args],
                            capture_output=True, text=True)
    return result.returncode, result.stdout + result.stderr


for how in (["--scene", str(work / "till.toml")], ["--axis=-x"]):
    code, out = run(*how, "--steady", "0.5", "1")
    if code != 0:
        failures.append(f"{how}: exit {code}: {out}")
    for wanted in ("draft force over 0.5–1 s: 50 ± 0 N (6 rows)",
                   "vertical force over 0.5–1 s: 20 ± 0 N", "lateral force over 0.5–1 s: -5 ± 0 N"):
        if wanted not in out:
            failures.append(f"{how}: '{wanted}' not in {out!r}")
    if not (work / "out.png").is_file():
        failures.append(f"{how}: no plot written")
    (work / "out.png").unlink(missing_ok=True)

code, out = run("--scene", str(work / "till.toml"))
for wanted in ("steady window 0.4857–1 s (the tool's pass through the bed)",
               "draft force over 0.486–1 s: 50 ± 0 N (6 rows)"):
    if code != 0 or wanted not in out:
        failures.append(f"the window of the pass: exit {code}: '{wanted}' not in {out!r}")
code, out = run("--scene", str(work / "till.toml"), "--entry-length", "0.5")
if code == 0 or "no steady window for mesh 'tine'" not in out:
    failures.append(f"a pass that never gets 0.5 m into the bed by t = 1 s: exit {code}: {out!r}")

code, out = run("--scene", str(work / "till.toml"), "--tool", "still")
if code == 0 or "mesh 'still'" not in out or "does not move" not in out:
    failures.append(f"a tool that does not move: exit {code}: {out!r}")
code, out = run("--tool", "blade")
if code == 0 or "no column 'blade_fx'" not in out:
    failures.append(f"a missing column: exit {code}: {out!r}")

for failure in failures:
    print(failure)
print(f"check_plot_draft: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
