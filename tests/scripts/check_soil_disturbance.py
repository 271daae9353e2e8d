#!/usr/bin/python3
"""Checks scripts/soil_disturbance.py on a synthetic pass whose disturbance is known exactly.

The bed is a simple cubic lattice of spheres (radius R, spacing d = 2R, so each surface cell of
the default size d holds one column), 40 × 30 columns of 8 layers from y = 0.003 m, each sphere
raised or lowered by up to 0.1 R at random. The pass takes the top 3 layers of the 6 columns at
y = 0.103..0.163 m (the furrow) onto the 6 columns beside it, mirrored (column j to 31 − j:
lateral throw 11, 9, .., 1 d), 3 d higher and 1, 2 or 3 d forward (by column); every other
sphere settles by 0.3 R. So, in the steady window (the middle half of the tool's path, from the
tool's mesh in the snapshots), the surface is 0.08 m before; after, 3 d + 0.3 R lower over the
furrow, 3 d higher over the ridge and 0.3 R lower elsewhere (below the default tolerance R, so
no area there). Each bin's surface is the mean of cell tops that lie within 0.1 R of the
lattice's, so its change lies within 0.2 R of the construction and an area over 6 bins within
6 d × 0.2 R. The thrown surface particles (one per furrow column and row) move by exactly known
amounts: forward 1, 2, 3 d in equal numbers, lateral 1..11 d, vertical 3 d.
Run twice: travel +x from --axis (BEFORE a bed file) and the mirrored pass along −x from a scene
(BEFORE and AFTER from an output folder's particles.xmf), then bad inputs, each refused with
exit 2 before anything is written.

Usage: check_soil_disturbance.py SOURCE_DIR WORK_DIR
"""
import json
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

R = 0.005
D = 2 * R
NX, NY, NZ = 40, 30, 8
Y0 = 0.003  # the bed's side: the cells across must span the bed, not start at y = 0
FURROW = range(10, 16)  # columns cut 3 layers deep, thrown to column 31 - j
DEPTH = 3
SETTLE = 0.3 * R
JITTER = 0.1 * R
failures = []


def forward_shift(j):
    return (j % 3 + 1) * D


def bed_before():
    """Positions and ids of the lattice, each sphere moved up or down by up to JITTER."""
    i, j, k = np.meshgrid(np.arange(NX), np.arange(NY), np.arange(NZ), indexing="ij")
    position = (np.stack([i, j, k], axis=-1).reshape(-1, 3) + 0.5) * D + [0.0, Y0, 0.0]
    position[:, 2] += np.random.default_rng(7).uniform(-JITTER, JITTER, len(position))
    return position, np.arange(len(position), dtype=np.uint64) + 1000


def after_pass(position):
    """The positions after the pass: the furrow's top layers thrown, the rest settled."""
    after = position.copy()
    column = np.rint((position[:, 1] - Y0) / D - 0.5).astype(int)
    layer = np.rint(position[:, 2] / D - 0.5).astype(int)
    thrown = np.isin(column, FURROW) & (layer >= NZ - DEPTH)
    after[thrown, 0] += forward_shift(column[thrown])
    after[thrown, 1] += (31 - 2 * column[thrown]) * D
    after[thrown, 2] += DEPTH * D
    after[~thrown, 2] -= SETTLE
    return after


def box(x0, x1):
    """The 8 corners of a tool-like box from x0 to x1 above the furrow."""
    return np.array([(x, y, z) for x in (x0, x1) for y in (0.103, 0.163) for z in (0.05, 0.3)])


def write_snapshot(path, position, ids, tool, time):
    with h5py.File(path, "w") as f:
        f["position"] = position
        f["radius"] = np.full(len(position), R)
        f["id"] = ids
        f["connectivity"] = np.arange(len(position), dtype=np.uint32)
        if tool is not None:
            f["mesh/sweep/vertices"] = tool
        f.attrs["time"], f.attrs["step"] = time, np.uint64(time * 1e4)


def write_bed(path, position, ids):
    with h5py.File(path, "w") as f:
        f["position_radius"] = np.column_stack([position, np.full(len(position), R)])
        f["id"] = ids


def write_xmf(folder, files):
    grids = "".join(f'<Grid Name="{name}" GridType="Uniform"><Time Value="{k}"/><Geometry '
                    f'GeometryType="XYZ"><DataItem Format="HDF">{name}:/position</DataItem>'
                    '</Geometry></Grid>' for k, name in enumerate(files))
    (folder / "particles.xmf").write_text(
        '<?xml version="1.0"?><Xdmf Version="3.0"><Domain><Grid Name="particles" '
        f'GridType="Collection" CollectionType="Temporal">{grids}</Grid></Domain></Xdmf>\n')


def close(what, value, expected, tolerance):
    if not abs(value - expected) <= tolerance:
        failures.append(f"{what}: {value!r}, expected {expected!r} ± {tolerance:g}")


def expected_surface(j):
    """The surface height of column j before and after the pass (up to JITTER)."""
    if j in FURROW:
        return 0.08, 0.08 - DEPTH * D - SETTLE
    if 31 - j in FURROW:
        return 0.08, 0.08 + DEPTH * D
    return 0.08, 0.08 - SETTLE


def check_profile(label, out):
    rows = np.loadtxt(out / "profile.csv", delimiter=",", skiprows=1, ndmin=2)
    if rows.shape != (NY, 3):
        failures.append(f"{label}: profile.csv has shape {rows.shape}, expected {(NY, 3)}")
        return
    for j, (y, before, after) in enumerate(rows):
        close(f"{label}: bin {j} centre", y, Y0 + (j + 0.5) * D, 1e-12)
        close(f"{label}: bin {j} before", before, expected_surface(j)[0], JITTER + 1e-12)
        close(f"{label}: bin {j} after", after, expected_surface(j)[1], JITTER + 1e-12)


def check_throw(label, throw, lateral_sign):
    """The throw statistics: forward 1, 2, 3 d and lateral 1, 3, .., 11 d, each value by one
    furrow column in every row of the window (14 rows: the 5th and 95th percentiles are the
    extreme values), vertical 3 d."""
    lateral = sorted(lateral_sign * v for v in (1, 11))
    wanted = {"forward": {"mean": 2 * D, "std": D * (2 / 3) ** 0.5, "p5": D, "p50": 2 * D,
                          "p95": 3 * D},
              "lateral": {"mean": lateral_sign * 6 * D, "std": D * (70 / 6) ** 0.5,
                          "p5": lateral[0] * D, "p50": lateral_sign * 6 * D, "p95": lateral[1] * D},
              "vertical": {"mean": 3 * D, "std": 0.0, "p5": 3 * D, "p50": 3 * D, "p95": 3 * D}}
    for name, stats in wanted.items():
        for key, value in stats.items():
            close(f"{label}: {name} throw {key}", (throw.get(name) or {}).get(key, np.nan),
                  value, 1e-12)


def check_summary(label, out, window, rows):
    summary = json.loads((out / "summary.json").read_text())
    for k in range(2):
        close(f"{label}: window end {k}", summary["window_m"][k], window[k], 1e-12)
    area_error = len(FURROW) * D * 2 * JITTER
    close(f"{label}: cut area", summary["cut_area_m2"], len(FURROW) * D * (DEPTH * D + SETTLE),
          area_error)
    close(f"{label}: ridge area", summary["ridge_area_m2"], len(FURROW) * D * DEPTH * D,
          area_error)
    close(f"{label}: ridge height", summary["ridge_height_m"], DEPTH * D, 2 * JITTER)
    close(f"{label}: cut depth", summary["cut_depth_m"], DEPTH * D + SETTLE, 2 * JITTER)
    close(f"{label}: disturbed width", summary["disturbed_width_m"], 2 * len(FURROW) * D, 1e-12)
    counts = {"surface_particles": NY * rows, "matched": NY * rows, "thrown": len(FURROW) * rows}
    for key, value in counts.items():
        if summary.get(key) != value:
            failures.append(f"{label}: {key} {summary.get(key)}, expected {value}")
    check_throw(label, summary["throw_m"], 1 if summary["travel"] == "+x" else -1)


def run(script, *args):
    return subprocess.run(["/usr/bin/python3", str(script), *map(str, args)],
                          capture_output=True, text=True)


def check_run(label, result, out, window, rows):
    if result.returncode != 0:
        failures.append(f"{label}: exit {result.returncode}: {result.stderr}")
        return
    check_profile(label, out)
    check_summary(label, out, window, rows)
    for png in ("profile.png", "throw.png"):
        if not (out / png).is_file():
            failures.append(f"{label}: no {png}")


def forward_pass(script, work, position, ids):
    """Travel +x (the default axis); BEFORE a bed file, the tool's rear at x = 0.30 in AFTER:
    window 0.005 + (0.30 − 0.005) × [1/4, 3/4] = 0.07875..0.22625, cut to 14 whole cells
    (0.07875..0.21875: x centres 0.085..0.215)."""
    write_bed(work / "bed.h5", position, ids)
    write_snapshot(work / "after.h5", after_pass(position), ids, box(0.30, 0.36), 0.5)
    result = run(script, work / "bed.h5", work / "after.h5", work / "plus_x")
    check_run("+x", result, work / "plus_x", (0.07875, 0.21875), 14)
    return result


def mirrored_pass(script, work, position, ids):
    """The pass mirrored to travel −x, from a scene, BEFORE and AFTER from an output folder:
    the tool's front at x = 0.38 before and its rear at 0.10 after, window 0.31..0.17 (14
    whole cells from x = 0.31 down: x centres 0.305..0.175)."""
    folder = work / "mirrored"
    folder.mkdir()
    mirror = np.array([-1.0, 1.0, 1.0])
    offset = np.array([NX * D, 0.0, 0.0])
    write_snapshot(folder / "particles_000000.h5", offset + mirror * position, ids,
                   box(0.38, 0.44), 0.0)
    write_snapshot(folder / "particles_000001.h5", offset + mirror * after_pass(position), ids,
                   box(0.04, 0.10), 0.5)
    write_xmf(folder, ["particles_000000.h5", "particles_000001.h5"])
    (work / "till.toml").write_text(
        '[[mesh]]\nname = "sweep"\nfile = "sweep.stl"\n\n[mesh.motion]\ntimes = [0, 1]\n'
        'velocities = [[-0.7, 0, 0], [-0.7, 0, 0]]\n')
    result = run(script, folder, folder / "particles.xmf", work / "minus_x",
                 "--scene", work / "till.toml")
    check_run("-x", result, work / "minus_x", (0.17, 0.31), 14)


def bad_inputs(work, position, ids):
    """(label, arguments, a text the message must hold) for inputs that must be refused."""
    after = work / "after.h5"
    (work / "junk.h5").write_text("not HDF5\n")
    write_snapshot(work / "strangers.h5", after_pass(position), ids + 10**6, box(0.3, 0.36), 0.5)
    write_snapshot(work / "no_mesh.h5", after_pass(position), ids, None, 0.5)
    with h5py.File(work / "no_id.h5", "w") as f:
        f["position"], f["radius"] = position, np.full(len(position), R)
    broken = work / "broken"
    broken.mkdir()
    shutil.copy(work / "bed.h5", broken / "particles_000000.h5")
    write_xmf(broken, ["particles_000000.h5", "particles_000001.h5"])
    return [("missing file", [work / "missing.h5", after], "missing.h5"),
            ("not HDF5", [work / "junk.h5", after], "junk.h5"),
            ("no id dataset", [work / "no_id.h5", after], "'id'"),
            ("snapshot missing from the index", [broken, broken], "particles_000001.h5"),
            ("vertical axis", [work / "bed.h5", after, "--axis=z"], "--axis"),
            ("percentile 0", [work / "bed.h5", after, "--percentile", "0"], "--percentile"),
            ("missing scene", [work / "bed.h5", after, "--scene", work / "none.toml"], "--scene"),
            ("window beyond the bed", [work / "bed.h5", after, "--window", "1.0", "1.1"],
             "empty steady window"),
            ("no mesh for the window", [work / "bed.h5", work / "no_mesh.h5"], "no mesh 'sweep'"),
            ("ids unmatched", [work / "bed.h5", work / "strangers.h5"], "strangers.h5")]


def check_refusals(script, work, position, ids):
    for label, args, needle in bad_inputs(work, position, ids):
        out = work / "refused"
        result = run(script, args[0], args[1], out, *args[2:])
        if result.returncode != 2 or needle not in result.stderr:
            failures.append(f"{label}: exit {result.returncode}, expected 2 with '{needle}': "
                            f"{result.stderr.strip()}")
        if out.exists():
            failures.append(f"{label}: {out} written although refused")


def main():
    script = pathlib.Path(sys.argv[1]) / "scripts" / "soil_disturbance.py"
    work = pathlib.Path(sys.argv[2])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    position, ids = bed_before()
    print(forward_pass(script, work, position, ids).stdout, end="")
    mirrored_pass(script, work, position, ids)
    check_refusals(script, work, position, ids)
    for failure in failures:
        print(failure)
    print(f"check_soil_disturbance: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
