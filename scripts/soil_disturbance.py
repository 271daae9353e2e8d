#!/usr/bin/python3
"""Measures the soil disturbance of a tillage pass from particle snapshots before and after it:
the furrow cross-section, the cut and ridge areas, the ridge height and the throw of the surface.

Usage: scripts/soil_disturbance.py BEFORE AFTER OUT_DIR [--axis=AXIS | --scene TOML]
       [--tool NAME] [--window A B] [--cell W] [--percentile P] [--layer T] [--moved D]
       [--tolerance T]

BEFORE and AFTER are HDF5 files: solver snapshots (datasets position, radius, id) or bed and
checkpoint files (position_radius, id); or an output folder or its particles.xmf, meaning its
first snapshot for BEFORE and its last for AFTER. The travel is along AXIS (x, -x, y or -y;
default x) or, with --scene, along the first non-zero velocity of mesh NAME (default sweep) in
that scene's [mesh.motion] (scripts/plot_draft.py). The steady window is the range A..B of the
travel axis's coordinate; by default the middle half of the tool's path through the soil: from
the soil's start (its first particle centre, or the tool's front in BEFORE if further on) to
the tool's rear in AFTER (from the snapshots' /mesh/NAME/vertices).

The ground is cut into square cells about W wide (default: one mean diameter): across the
travel a whole number of them spans BEFORE's soil (from its particles' extent), along it the
window is cut to the whole cells that fit in it from its start. A cell's surface height is the
P-th percentile (default 100: the highest) of the tops z + r of its particles, the whole column
under it; the profile of a bin across the travel is the mean of its cells in the window.
Where the profile after differs from the one before by more than T (default: one mean radius),
the soil moved: the cut area is the area lost below the original surface, the ridge area the
area gained above it, the ridge height the highest rise (the cut depth the deepest fall). The
surface particles are those of the window whose top lies within --layer (default one mean
radius) of their cell's surface before the pass; matched by id, those that moved at least D
(default one mean diameter) are the thrown ones: their forward, lateral (to the left of the
travel) and vertical displacements give the throw's histograms, mean, standard deviation and
5th, 50th and 95th percentiles.

Writes OUT_DIR/profile.csv, summary.json, profile.png and throw.png. Exit 2 on bad input,
before writing anything.
"""
import argparse
import collections
import csv
import json
import pathlib
import sys
import xml.etree.ElementTree as ET

import numpy as np

try:
    import h5py
except ImportError:
    sys.exit("soil_disturbance.py needs h5py (Debian: python3-h5py); run it with /usr/bin/python3")

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import plot_draft  # noqa: E402  (also selects matplotlib's Agg backend)
import tool_travel  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

Particles = collections.namedtuple("Particles", "path position radius ids tool")
Travel = collections.namedtuple("Travel", "axis direction")  # axis 0 (x) or 1 (y); unit vector
# Cells `width` wide: `along_cells` of them from `start` (a coordinate along the travel
# direction), and across from `low` (the bed's side) on.
Grid = collections.namedtuple("Grid", "travel start along_cells low width")
UP = np.array([0.0, 0.0, 1.0])
ACROSS_NAMES = "yx"  # the coordinate across a travel along x, along y


def fail(message):
    print(f"soil_disturbance.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def snapshot_file(path, last):
    """The HDF5 file `path` names: itself, or the first (last) snapshot an .xmf index lists (an
    output folder: its particles.xmf)."""
    path = pathlib.Path(path)
    if path.is_dir():
        path = path / "particles.xmf"
    if path.suffix != ".xmf":
        return path
    try:
        grids = ET.parse(path).getroot().findall("Domain/Grid/Grid")
    except (OSError, ET.ParseError) as error:
        fail(f"{path}: {error}")
    item = grids[-1 if last else 0].find("Geometry/DataItem") if grids else None
    if item is None:
        fail(f"{path}: lists no snapshot with a Geometry DataItem")
    return path.parent / (item.text or "").strip().partition(":")[0]


def read_particles(path, tool):
    """The particles of a snapshot, bed or checkpoint file, and the vertices of mesh `tool`
    (None when the file has none)."""
    if not pathlib.Path(path).is_file():
        fail(f"{path}: no such file")
    try:
        with h5py.File(path, "r") as f:
            names = ["position_radius"] if "position_radius" in f else ["position", "radius"]
            missing = [n for n in names + ["id"] if not isinstance(f.get(n), h5py.Dataset)]
            if missing:
                fail(f"{path}: no dataset '{missing[0]}' (snapshots need the fields radius, id)")
            data = {n: np.asarray(f[n]) for n in names + ["id"]}
            vertices = f.get(f"mesh/{tool}/vertices")
            vertices = None if vertices is None else np.asarray(vertices)
    except OSError as error:
        fail(f"{path}: not a readable HDF5 file: {error}")
    packed = data.pop("position_radius", None)
    if packed is not None:
        data["position"], data["radius"] = packed[:, :3], packed[:, 3]
    if len(data["id"]) == 0 or len(data["position"]) != len(data["id"]):
        fail(f"{path}: no particles, or not one id per particle")
    return Particles(path, data["position"], data["radius"], data["id"], vertices)


def travel_of(args):
    """The travel axis and direction, from --scene or --axis: horizontal, along x or y."""
    if args.scene:
        try:
            tool = tool_travel.find_tool(tool_travel.load_scene(args.scene), args.scene, args.tool)
        except tool_travel.SceneError as error:
            fail(f"--scene: {error}")
        direction, up = tool.travel, tool.up
        if np.dot(up, UP) < 1 - 1e-9:
            fail(f"--scene {args.scene}: its gravity is not along -z")
    else:
        direction = plot_draft.axis_direction(args.axis)
    direction = np.asarray(direction, dtype=float)
    axis = int(np.argmax(np.abs(direction)))
    if axis == 2 or abs(abs(direction[axis]) - 1) > 1e-9:
        fail(f"the travel {tuple(direction)} is not along x or y")
    return Travel(axis, direction)


def tool_path_window(before, after, travel, tool):
    """The middle half of the tool's path through the soil, as a range of the coordinate along
    the travel: from the soil's start (the first particle centre, or the tool's front in BEFORE
    when further on) to the tool's rear in AFTER."""
    if after.tool is None:
        fail(f"{after.path}: no mesh '{tool}' to place the window; give --window or --tool")
    start = (before.position @ travel.direction).min()
    if before.tool is not None:
        start = max(start, (before.tool @ travel.direction).max())
    end = (after.tool @ travel.direction).min()
    if end <= start:
        fail(f"empty steady window: the tool's rear in {after.path} has not passed the soil's "
             "start; give --window")
    return 0.75 * start + 0.25 * end, 0.25 * start + 0.75 * end


def grid_of(before, window, travel, cell):
    """Square cells about `cell` wide: across the travel, a whole number of them spanning the
    soil of BEFORE (its particles' extent); along it, the whole cells that fit in the window
    from its start."""
    across = before.position[:, 1 - travel.axis]
    low, high = (across - before.radius).min(), (across + before.radius).max()
    across_cells = max(1, round((high - low) / cell))
    width = (high - low) / across_cells
    along_cells = int(np.floor((window[1] - window[0]) / width * (1 + 1e-9)))
    if along_cells < 1:
        fail(f"empty steady window: {window[1] - window[0]:g} m long, less than a cell "
             f"({width:g} m)")
    return Grid(travel, window[0], along_cells, low, width)


def world_window(grid):
    """The whole cells along the travel, as a range of the travel axis's coordinate."""
    sign = grid.travel.direction[grid.travel.axis]
    ends = grid.start, grid.start + grid.along_cells * grid.width
    return sorted(float(sign * end) for end in ends)


def window_surface(particles, grid, percentile):
    """The particles inside the grid's window (a mask), the cells (along index, across index)
    holding them, each cell's surface height (the percentile of its particles' tops z + r)
    and the cell of each particle in the window."""
    along = (particles.position @ grid.travel.direction - grid.start) / grid.width
    across = (particles.position[:, 1 - grid.travel.axis] - grid.low) / grid.width
    inside = (along >= 0) & (along < grid.along_cells)
    if not inside.any():
        a, b = world_window(grid)
        fail(f"empty steady window {a:g}..{b:g} m: {particles.path} has no particle in it")
    top = particles.position[inside, 2] + particles.radius[inside]
    keys = np.floor(np.column_stack([along, across])[inside]).astype(np.int64)
    cells, of_particle = np.unique(keys, axis=0, return_inverse=True)
    of_particle = of_particle.reshape(-1)
    groups = np.split(top[np.argsort(of_particle, kind="stable")],
                      np.cumsum(np.bincount(of_particle))[:-1])
    heights = np.array([np.percentile(g, percentile) for g in groups])
    return inside, cells, heights, of_particle


def profile(cells, heights):
    """The across bins and each bin's mean surface height over its cells along the travel."""
    bins, of_cell = np.unique(cells[:, 1], return_inverse=True)
    return bins, np.bincount(of_cell, weights=heights) / np.bincount(of_cell)


def disturbance(z_before, z_after, width, tolerance):
    """Cut and ridge areas of the bins whose surface moved more than `tolerance`, ridge height
    and cut depth (the highest rise and the deepest fall), and the width that moved."""
    rise = z_after - z_before
    moved = np.abs(rise) > tolerance
    return {"cut_area_m2": float(width * -rise[moved & (rise < 0)].sum()),
            "ridge_area_m2": float(width * rise[moved & (rise > 0)].sum()),
            "ridge_height_m": float(max(rise.max(), 0.0)),
            "cut_depth_m": float(max(-rise.min(), 0.0)),
            "disturbed_width_m": float(width * np.count_nonzero(moved))}


def surface_throw(before, after, surface, travel, layer, moved):
    """Displacements (forward, lateral to the left, vertical) of the surface particles of the
    window that moved at least `moved`, and the counts of surface, matched and thrown ones."""
    inside, _, heights, of_particle = surface
    top = (before.position[:, 2] + before.radius)[inside]
    on_surface = top >= heights[of_particle] - layer
    ids = before.ids[inside][on_surface]
    _, in_before, in_after = np.intersect1d(ids, after.ids, return_indices=True)
    if len(in_before) == 0:
        fail(f"no surface particle of {before.path} has its id in {after.path}")
    delta = after.position[in_after] - before.position[inside][on_surface][in_before]
    thrown = np.linalg.norm(delta, axis=1) >= moved
    axes = {"forward": travel.direction, "lateral": np.cross(UP, travel.direction), "vertical": UP}
    throw = {name: delta[thrown] @ axis for name, axis in axes.items()}
    counts = {"surface_particles": int(len(ids)), "matched": int(len(in_before)),
              "thrown": int(np.count_nonzero(thrown))}
    return throw, counts


def statistics(values):
    """Mean, standard deviation and 5th, 50th and 95th percentiles (None when there are none)."""
    if len(values) == 0:
        return None
    p5, p50, p95 = np.percentile(values, [5, 50, 95])
    return {"mean": float(values.mean()), "std": float(values.std()), "p5": float(p5),
            "p50": float(p50), "p95": float(p95)}


def plot_profile(path, across, z_before, z_after, summary):
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(across, z_before, "k-", lw=1, label="before")
    ax.plot(across, z_after, "C0-", lw=1.5, label="after")
    rise, tolerance = z_after - z_before, summary["tolerance_m"]
    ax.fill_between(across, z_before, z_after, where=rise < -tolerance, color="C3", alpha=0.4,
                    label=f"cut {summary['cut_area_m2'] * 1e4:.1f} cm²")
    ax.fill_between(across, z_before, z_after, where=rise > tolerance, color="C2", alpha=0.4,
                    label=f"ridge {summary['ridge_area_m2'] * 1e4:.1f} cm², "
                          f"{summary['ridge_height_m'] * 1e3:.1f} mm high")
    a, b = summary["window_m"]
    axis = summary["travel"][-1]
    ax.set_title(f"surface across the travel ({summary['travel']}), mean over {axis} = "
                 f"{a:.3f}–{b:.3f} m")
    ax.set_xlabel(f"{summary['across']} [m]")
    ax.set_ylabel("surface height z [m]")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def plot_throw(path, throw, summary):
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.5))
    for ax, (name, values) in zip(axes, throw.items()):
        ax.hist(values * 1e3, bins=30, color="C0")
        ax.set_xlabel(f"{name} displacement [mm]")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("surface particles")
    fig.suptitle(f"throw of the {summary['thrown']} surface particles that moved at least "
                 f"{summary['moved_m'] * 1e3:.1f} mm (lateral: to the left of the travel)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def write_outputs(out_dir, table, summary, throw):
    out_dir.mkdir(parents=True, exist_ok=True)
    across, z_before, z_after = table
    with open(out_dir / "profile.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow([summary["across"], "z_before", "z_after"])
        writer.writerows(zip(across, z_before, z_after))
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    plot_profile(out_dir / "profile.png", across, z_before, z_after, summary)
    plot_throw(out_dir / "throw.png", throw, summary)


def print_summary(summary):
    a, b = summary["window_m"]
    print(f"window {summary['travel'][-1]} = {a:.4g}..{b:.4g} m, cells {summary['cell_m']:.4g} m: "
          f"{summary['surface_particles']} surface particles, {summary['matched']} matched, "
          f"{summary['thrown']} thrown")
    print(f"cut area {summary['cut_area_m2']:.4g} m^2, ridge area {summary['ridge_area_m2']:.4g} "
          f"m^2, ridge height {summary['ridge_height_m']:.4g} m, cut depth "
          f"{summary['cut_depth_m']:.4g} m, disturbed width {summary['disturbed_width_m']:.4g} m")
    for name, stats in summary["throw_m"].items():
        text = "none" if stats is None else (
            f"mean {stats['mean']:.4g} m, std {stats['std']:.4g} m, p5 {stats['p5']:.4g} m, "
            f"p50 {stats['p50']:.4g} m, p95 {stats['p95']:.4g} m")
        print(f"{name} throw: {text}")


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("before", help="HDF5 file, or output folder / .xmf (its first snapshot)")
    parser.add_argument("after", help="HDF5 file, or output folder / .xmf (its last snapshot)")
    parser.add_argument("out_dir", help="folder for profile.csv, summary.json and the plots")
    direction = parser.add_mutually_exclusive_group()
    direction.add_argument("--scene", metavar="TOML", help="travel along mesh NAME's motion")
    direction.add_argument("--axis", default="x", choices=["x", "-x", "y", "-y"],
                           help="travel direction (default x)")
    parser.add_argument("--tool", default="sweep", metavar="NAME", help="default sweep")
    parser.add_argument("--window", nargs=2, type=float, metavar=("A", "B"),
                        help="m along the travel axis; default the middle of the tool's path")
    parser.add_argument("--cell", type=float, metavar="W", help="m; default one mean diameter")
    parser.add_argument("--percentile", type=float, default=100.0, metavar="P",
                        help="of the tops in a cell: its surface (default 100, the highest)")
    parser.add_argument("--layer", type=float, metavar="T",
                        help="surface layer, m; default one mean radius")
    parser.add_argument("--moved", type=float, metavar="D",
                        help="least throw counted, m; default one mean diameter")
    parser.add_argument("--tolerance", type=float, metavar="T",
                        help="least change of the profile counted, m; default one mean radius")
    args = parser.parse_args()
    if args.cell is not None and args.cell <= 0:
        parser.error("--cell must be positive")
    if not 0 < args.percentile <= 100:
        parser.error("--percentile must lie in (0, 100]")
    for name in ("layer", "moved", "tolerance"):
        if getattr(args, name) is not None and getattr(args, name) < 0:
            parser.error(f"--{name} must not be negative")
    return args


def lengths(args, radius):
    """--cell, --layer, --moved and --tolerance, each defaulting to a multiple of the mean
    radius of BEFORE's particles."""
    defaults = {"cell": 2 * radius, "layer": radius, "moved": 2 * radius, "tolerance": radius}
    return {name: default if getattr(args, name) is None else getattr(args, name)
            for name, default in defaults.items()}


def measure(args):
    """The profile table, the summary and the throw of the pass the arguments describe."""
    travel = travel_of(args)
    before = read_particles(snapshot_file(args.before, last=False), args.tool)
    after = read_particles(snapshot_file(args.after, last=True), args.tool)
    length = lengths(args, float(before.radius.mean()))
    sign = travel.direction[travel.axis]
    window = (sorted(sign * end for end in args.window) if args.window
              else tool_path_window(before, after, travel, args.tool))
    grid = grid_of(before, window, travel, length["cell"])
    surface_before = window_surface(before, grid, args.percentile)
    bins_before, z_before = profile(*surface_before[1:3])
    bins_after, z_after = profile(*window_surface(after, grid, args.percentile)[1:3])
    bins, in_before, in_after = np.intersect1d(bins_before, bins_after, return_indices=True)
    table = (grid.low + (bins + 0.5) * grid.width, z_before[in_before], z_after[in_after])
    throw, counts = surface_throw(before, after, surface_before, travel, length["layer"],
                                  length["moved"])
    summary = {"before": str(before.path), "after": str(after.path),
               "travel": ("+" if sign > 0 else "-") + "xy"[travel.axis],
               "across": ACROSS_NAMES[travel.axis], "window_m": world_window(grid),
               "percentile": args.percentile,
               **{f"{name}_m": value for name, value in length.items()}, "cell_m": grid.width,
               **disturbance(*table[1:], grid.width, length["tolerance"]), **counts,
               "throw_m": {name: statistics(values) for name, values in throw.items()}}
    return table, summary, throw


def main():
    args = parse_args()
    out_dir = pathlib.Path(args.out_dir)
    if out_dir.exists() and not out_dir.is_dir():
        fail(f"{out_dir}: exists and is not a folder")
    table, summary, throw = measure(args)
    write_outputs(out_dir, table, summary, throw)
    print_summary(summary)
    print(f"written: {out_dir}/profile.csv, summary.json, profile.png, throw.png")


if __name__ == "__main__":
    main()
