#!/usr/bin/python3
"""The hard cases of inputs/hard/, each run through gpudem-mpi and checked against what a run
must do there (docs/validation.md, "Hard cases").

- projectile: a 2.5 mm glass sphere at 750 m/s into 2,000 loose glass grains (Hertz-Mindlin,
  E = 70 GPa). Ten times faster (7,500 m/s) is refused at start-up (exit 2, nothing written)
  with the predicted overlap and the speed the contact holds. At 750 m/s, at dt_fraction 0.1,
  0.05 and 0.025, every run keeps its 2,001 particles, never overlaps by half a radius, and its
  total energy (kinetic + elastic, no gravity) never rises; the projectile's depth at the end
  converges as dt halves (the second difference smaller than the first and under 0.1 mm).
- settle SCENE: a bed poured and settled (polydisperse_bed.toml, stiffness_contrast_bed.toml):
  it runs to its end, keeps every particle, never overlaps by half a radius, and its kinetic
  energy at the end is under 5 % of its peak (in the 10:1 bed small grains still sift through
  the large ones' gaps long after the pour).
- tool: a plate (fast_tool.toml, 0.06 m × 0.05 m in a plane x = const) driven at 5 m/s through
  1,500 grains, every step written: no grain's centre passes from one side of the plate to the
  other between two steps while its (y, z) lies on the plate, no grain overlaps the plate by
  half its radius, and none leaves the domain.
- unstable: dt about eight times the stable limit, allowed (unstable_dt.toml): the run stops
  with exit 3, names the step and particle, and writes its last state.
- piston: first one glass sphere between the floor and a piston pressed by 10 N, no gravity:
  at rest the piston has come down by the two Hertz overlaps of that force,
  2 (3P / (4 E* sqrt(R)))^(2/3), within 0.1 %, and the sphere's push equals the load (within
  10^-6); then
  loaded_piston.toml, stiff grains (E = 70 GPa, R = 1 mm) under a loaded piston for over 10^6
  steps: every grain kept, no overlap of half a radius, the piston's push balances its load and
  weight at the end (within 0.1 %), the packing holds its height over the last 60 % of the run
  (the piston moves by less than 0.2 % of a radius, 2 µm), and the kinetic energy, once down to
  10^-8 of its peak, never climbs back above 10^-7 of it and ends below 10^-10 of it.

Every run's time series and snapshots hold no NaN or infinity.
Usage: check_hard_cases.py [--backend host|cuda] CASE SOURCE_DIR GPUDEM_BINARY WORK_DIR [SCENE]
Every run uses the backend given (default host); with cuda, where this build has no CUDA backend
or no device is visible, the case is skipped (exit 77, ctest's SKIP_RETURN_CODE), saying why.
"""
import csv
import glob
import math
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

FAILURES = []
BACKEND = ["host"]  # the backend of every run (main sets it)
SKIPPED = 77  # ctest's SKIP_RETURN_CODE


def check(condition, message):
    if not condition:
        FAILURES.append(message)
        print("FAIL:", message)


def run(binary, scene, out, *sets):
    command = [binary, str(scene), "--backend", BACKEND[0], "--quiet", "--output-dir", str(out)]
    for s in sets:
        command += ["--set", s]
    return subprocess.run(command, capture_output=True, text=True)


def rows_of(out):
    return list(csv.DictReader(open(out / "timeseries.csv")))


def finished_rows(binary, scene, out, label):
    """Runs `scene` into `out`: its time-series rows, or None (a failure) when it did not
    exit 0."""
    r = run(binary, scene, out)
    check(r.returncode == 0, f"{label}: exit {r.returncode}\n{r.stderr}")
    return rows_of(out) if r.returncode == 0 else None


def check_finite_output(out, label):
    """No NaN or infinity in the time series or any snapshot dataset."""
    values = [float(v) for row in rows_of(out) for v in row.values()]
    check(all(math.isfinite(v) for v in values), f"{label}: a non-finite value in the CSV")
    for name in sorted(glob.glob(str(out / "particles_*.h5"))):
        with h5py.File(name, "r") as f:
            for key, data in f.items():
                if isinstance(data, h5py.Dataset) and data.dtype.kind == "f":
                    check(np.all(np.isfinite(data[:])), f"{label}: {name} {key} not finite")


def check_kept_and_held(rows, count, label):
    check(all(int(row["particles"]) == count and row["removed"] == "0" for row in rows),
          f"{label}: particles lost")
    deepest = max(float(row["max_overlap_ratio"]) for row in rows)
    check(deepest < 0.5, f"{label}: an overlap reached {deepest} of a radius")
    return deepest


def projectile_z(out):
    """The projectile's (id 0) z at the last snapshot [m]."""
    with h5py.File(sorted(glob.glob(str(out / "particles_*.h5")))[-1], "r") as f:
        return float(f["position"][int(np.where(f["id"][:] == 0)[0][0])][2])


def projectile_run(binary, scene, work, fraction):
    out = work / f"dt{fraction}"
    r = run(binary, scene, out, f"simulation.dt_fraction={fraction}")
    check(r.returncode == 0, f"dt_fraction {fraction}: exit {r.returncode}\n{r.stderr}")
    if r.returncode != 0:
        return math.nan
    rows = rows_of(out)
    deepest = check_kept_and_held(rows, 2001, f"dt_fraction {fraction}")
    energy = [float(row["kinetic_translational"]) + float(row["kinetic_rotational"]) +
              float(row["potential_elastic"]) for row in rows]
    rise = max(b - max(energy[: k + 1]) for k, b in enumerate(energy[1:]))
    check(rise <= 1e-9 * energy[0], f"dt_fraction {fraction}: energy rose by {rise} J")
    check_finite_output(out, f"dt_fraction {fraction}")
    z = projectile_z(out)
    print(f"dt_fraction {fraction}: {len(rows)} rows, deepest overlap {deepest:.4f}, "
          f"energy {energy[0]:.4g} -> {energy[-1]:.4g} J, projectile z {z:.6f} m")
    return z


def projectile(source, binary, work):
    scene = source / "inputs" / "hard" / "projectile.toml"
    fast = work / "fast.csv"
    fast.write_text("x,y,z,r,vx,vy,vz\n0.015,0.015,0.036,0.0025,0,0,-7500\n")
    r = run(binary, scene, work / "fast", f'insert.0.csv="{fast}"')
    check(r.returncode == 2, f"7,500 m/s: exit {r.returncode}, expected 2\n{r.stderr}")
    check("would overlap by" in r.stderr and "holds impacts up to" in r.stderr,
          f"7,500 m/s: the refusal names no overlap or held speed:\n{r.stderr}")
    check(not (work / "fast").exists(), "7,500 m/s: the refused run wrote its output folder")
    z = [projectile_run(binary, scene, work, f) for f in (0.1, 0.05, 0.025)]
    first, second = abs(z[0] - z[1]), abs(z[1] - z[2])
    print(f"depth differences as dt halves: {first:.3g} m, {second:.3g} m")
    check(second < first and second < 1e-4, f"the depth does not converge: {z}")


def settle(source, binary, work, name):
    out = work / "out"
    rows = finished_rows(binary, source / "inputs" / "hard" / name, out, name)
    if rows is None:
        return
    deepest = check_kept_and_held(rows, int(rows[0]["particles"]), name)
    kinetic = [float(row["kinetic_translational"]) + float(row["kinetic_rotational"])
               for row in rows]
    check(kinetic[-1] < 0.05 * max(kinetic),
          f"{name}: not settled, {kinetic[-1]} of {max(kinetic)} J")
    check_finite_output(out, name)
    print(f"{name}: {rows[0]['particles']} particles, deepest overlap {deepest:.4f}, kinetic energy "
          f"{kinetic[-1]:.3g} J at the end, {max(kinetic):.3g} J at its peak")

PLATE = {"x0": 0.02, "speed": 5.0, "y": (0.02, 0.08), "z": (0.0, 0.05), "dt": 2e-5}


def snapshot_by_id(name):
    """Positions and radii of a snapshot, rows in id order."""
    with h5py.File(name, "r") as f:
        order = np.argsort(f["id"][:])
        return f["id"][:][order], f["position"][:][order], f["radius"][:][order]


def on_plate(position):
    y, z = position[:, 1], position[:, 2]
    return (y >= PLATE["y"][0]) & (y <= PLATE["y"][1]) & (z >= PLATE["z"][0]) & (z <= PLATE["z"][1])


def tool(source, binary, work):
    out = work / "out"
    rows = finished_rows(binary, source / "inputs" / "hard" / "fast_tool.toml", out, "fast_tool")
    if rows is None:
        return
    check_kept_and_held(rows, int(rows[0]["particles"]), "fast_tool")
    check_finite_output(out, "fast_tool")
    names = sorted(glob.glob(str(out / "particles_*.h5")))
    check(len(names) == 1001, f"fast_tool: {len(names)} snapshots, expected one per step (1,001)")
    crossings, deepest, before = 0, 0.0, None
    for step, name in enumerate(names):
        ids, position, radius = snapshot_by_id(name)
        side = position[:, 0] - (PLATE["x0"] + PLATE["speed"] * step * PLATE["dt"])
        plate_rows = on_plate(position)
        ahead = plate_rows & (side > 0)
        if ahead.any():
            deepest = max(deepest, float(np.max((radius[ahead] - side[ahead]) / radius[ahead])))
        if before is not None and np.array_equal(before[0], ids):
            crossed = before[2] & plate_rows & (np.sign(before[1]) != np.sign(side))
            crossings += int(np.count_nonzero(crossed))
        before = (ids, side, plate_rows)
    check(crossings == 0, f"fast_tool: {crossings} passages of a grain through the plate")
    check(deepest < 0.5, f"fast_tool: a grain overlapped the plate by {deepest} of its radius")
    print(f"fast_tool: {len(names)} snapshots, no grain through the plate, deepest overlap with "
          f"it {deepest:.4f} of a radius")


def unstable(source, binary, work):
    out = work / "out"
    r = run(binary, source / "inputs" / "hard" / "unstable_dt.toml", out)
    check(r.returncode == 3, f"unstable_dt: exit {r.returncode}, expected 3\n{r.stderr}")
    for words in ("unstable at step", "particle id", "last state written to"):
        check(words in r.stderr, f"unstable_dt: the stop does not say '{words}':\n{r.stderr}")
    last = r.stderr.split("last state written to ")[-1].split(".h5")[0] + ".h5"
    check(pathlib.Path(last).exists(), f"unstable_dt: the last state {last} is missing")
    check_finite_output(out, "unstable_dt")
    print(r.stderr.strip().splitlines()[-1])


SPHERE_UNDER_PISTON = """
[simulation]
end_time = 0.05
gravity = [0.0, 0.0, 0.0]
dt = "auto"
[domain]
min = [0.0, 0.0, 0.0]
max = [0.004, 0.004, 0.004]
[[material]]
name = "glass"
density = 2500.0
young = 7.0e10
poisson = 0.22
restitution = 0.5
friction = 0.3
[contact]
normal = "hertz"
damping = "restitution"
tangential = "mindlin"
[[wall]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "glass"
[[wall]]
name = "piston"
point = [0.0, 0.0, 0.002]
normal = [0.0, 0.0, -1.0]
material = "glass"
mass = 0.001
load = 10.0
[[insert]]
csv = "sphere.csv"
material = "glass"
[output]
every = 0.05
timeseries_every = 0.0005
"""


def sphere_under_piston(work):
    """A sphere of R = 1 mm touching the floor and the piston at t = 0."""
    (work / "sphere.csv").write_text("x,y,z,r\n0.002,0.002,0.001,0.001\n")
    scene = work / "sphere_under_piston.toml"
    scene.write_text(SPHERE_UNDER_PISTON)
    return scene


def piston(source, binary, work):
    rows = finished_rows(binary, sphere_under_piston(work), work / "sphere",
                         "sphere under a piston")
    if rows is not None:
        last = rows[-1]
        load, young, poisson, radius = 10.0, 7.0e10, 0.22, 0.001
        e_star = young / (2 * (1 - poisson ** 2))
        overlap = (3 * load / (4 * e_star * math.sqrt(radius))) ** (2 / 3)
        moved = float(last["piston_displacement"])
        check(abs(moved - 2 * overlap) < 1e-3 * 2 * overlap,
              f"sphere under a piston: it came down by {moved} m, Hertz gives {2 * overlap} m")
        push = float(last["piston_fz"])
        check(abs(push - load) < 1e-6 * load, f"sphere under a piston: push {push} N, load {load} N")
        print(f"sphere under a piston: down by {moved:.6e} m (Hertz {2 * overlap:.6e} m), "
              f"push {push:.6f} N")
    bed(source, binary, work)


def bed(source, binary, work):
    out = work / "bed"
    rows = finished_rows(binary, source / "inputs" / "hard" / "loaded_piston.toml", out,
                         "loaded_piston")
    if rows is None:
        return
    steps = int(float(rows[-1]["step"]))
    check(steps > 1_000_000, f"loaded_piston: {steps} steps, expected over 10^6")
    deepest = check_kept_and_held(rows, 200, "loaded_piston")
    check_finite_output(out, "loaded_piston")
    drive = 10.0 + 0.01 * 9.81
    push = float(rows[-1]["piston_fz"])
    check(abs(push - drive) < 1e-3 * drive, f"loaded_piston: push {push} N against {drive} N")
    late = [row for row in rows if float(row["time"]) >= 0.1]
    heights = [float(row["piston_displacement"]) for row in late]
    drift = max(heights) - min(heights)
    check(drift < 2e-6, f"loaded_piston: the piston moved {drift} m after t = 0.1 s")
    kinetic = [float(row["kinetic_translational"]) + float(row["kinetic_rotational"])
               for row in rows]
    peak = max(kinetic)
    down = next((k for k in range(kinetic.index(peak), len(kinetic))
                 if kinetic[k] < 1e-8 * peak), None)
    check(down is not None, f"loaded_piston: kinetic energy never fell to 1e-8 of {peak} J")
    check(kinetic[-1] < 1e-10 * peak, f"loaded_piston: {kinetic[-1]} J at the end (peak {peak} J)")
    if down is not None:
        after = max(kinetic[down:])
        check(after < 1e-7 * peak,
              f"loaded_piston: kinetic energy rose back to {after} J (peak {peak} J)")
        print(f"loaded_piston: {steps} steps, deepest overlap {deepest:.5f}, push {push:.6f} N "
              f"(load and weight {drive} N), piston moved {drift:.3g} m after 0.1 s, kinetic "
              f"energy {peak:.3g} J at its peak, under 1e-8 of it from t = "
              f"{rows[down]['time']} s, at most {after:.3g} J after, {kinetic[-1]:.3g} J at the end")


def backend_unavailable(source, binary, work):
    """Why BACKEND cannot run here (a build without CUDA, no device visible), or None; the host
    backend always can."""
    if BACKEND[0] == "host":
        return None
    r = run(binary, source / "inputs" / "hard" / "unstable_dt.toml", work / "probe",
            "simulation.end_time=1e-9", "output.every=0")
    if r.returncode == 0:
        return None
    for reason in ("this build has no CUDA backend", "no CUDA device is visible"):
        if reason in r.stderr:
            return reason
    sys.exit(f"probe of --backend {BACKEND[0]}: exit {r.returncode}\n{r.stderr}")


def main():
    args = sys.argv[1:]
    if args[:1] == ["--backend"]:
        BACKEND[0], args = args[1], args[2:]
    case, source, binary, work = args[0], pathlib.Path(args[1]), args[2], pathlib.Path(args[3])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    reason = backend_unavailable(source, binary, work)
    if reason:
        print(f"skipped: {reason}")
        sys.exit(SKIPPED)
    if case == "projectile":
        projectile(source, binary, work)
    elif case == "settle":
        settle(source, binary, work, args[4])
    elif case == "unstable":
        unstable(source, binary, work)
    elif case == "tool":
        tool(source, binary, work)
    elif case == "piston":
        piston(source, binary, work)
    else:
        sys.exit(f"unknown case {case}")
    if FAILURES:
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
