#!/usr/bin/python3
"""Plots the forces on a tillage tool over time: draft (against its travel), vertical and lateral,
each with its mean over the steady window.

Usage: scripts/plot_draft.py TIMESERIES_CSV OUT_PNG [--tool NAME] [--scene TOML | --axis=AXIS]
       [--steady START END | --entry-length M --exit-margin M] [--append-csv FILE --label TEXT]

The travel direction d is the tool's: with --scene, the direction of the first non-zero velocity
of the [[mesh]] named NAME in that scene's [mesh.motion]; else --axis=AXIS (x, -x, y, -y, z or
-z; default x). With F the tool's force (columns NAME_fx, NAME_fy, NAME_fz, default NAME = "sweep")
and u the upward unit vector (against the scene's gravity; +z without a scene): draft = −F·d,
vertical = F·u, lateral = F·(u × d) (to the left of the travel). The steady window is --steady
when given; else, with --scene, the window of the tool's pass through the bed (the rule of
scripts/tool_travel.py: from the time the tool's front is --entry-length into the bed until it
is --exit-margin before the bed's far face, both by default the tool's length along its travel,
or until the motion's last keyframe or the CSV's last row if earlier); else the second half of
the run. Prints the mean and standard deviation of each over the window and, with --append-csv,
appends the draft's to FILE as the row "TEXT,mean,std" (as printed).
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tool_travel import SceneError, cross, dot, find_tool, load_scene, steady_window  # noqa: E402

AXES = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}


def axis_direction(text):
    sign = -1 if text.startswith("-") else 1
    return tuple(sign * c for c in AXES[text.lstrip("-")])


def mean_std(values):
    mean = sum(values) / len(values)
    return mean, (sum((v - mean) ** 2 for v in values) / len(values)) ** 0.5


def read_rows(path, tool):
    """The rows of time series `path`, which must have the force columns of mesh `tool`."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    missing = [c for c in (f"{tool}_f{a}" for a in "xyz") if not rows or c not in rows[0]]
    if missing:
        raise ValueError(f"{path} has no column '{missing[0]}'")
    return rows


def components(rows, tool, travel, up):
    """Time and the draft, vertical and lateral force of each row."""
    lateral = cross(up, travel)
    time, out = [], {"draft": [], "vertical": [], "lateral": []}
    for r in rows:
        force = tuple(float(r[f"{tool}_f{c}"]) for c in "xyz")
        time.append(float(r["time"]))
        out["draft"].append(-dot(force, travel))
        out["vertical"].append(dot(force, up))
        out["lateral"].append(dot(force, lateral))
    return time, out


def plot(time, forces, window, tool, png):
    """Plots each force over time with its mean over `window`; returns {name: (mean, std,
    rows)} over the window."""
    start, end = window
    fig, axes = plt.subplots(3, 1, figsize=(7, 8), sharex=True)
    stats = {}
    for ax, (name, values) in zip(axes, forces.items()):
        steady = [v for t, v in zip(time, values) if start <= t <= end]
        stats[name] = (*mean_std(steady), len(steady))
        mean, std, _ = stats[name]
        ax.plot(time, values, lw=0.8, label=f"{name} force")
        ax.hlines(mean, start, end, colors="C3", lw=2,
                  label=f"mean {start:.2f}–{end:.2f} s: {mean:.1f} ± {std:.1f} N")
        ax.set_ylabel(f"{name} [N]")
        ax.grid(alpha=0.3)
        ax.legend(loc="lower right")
    axes[0].set_title(f"{tool}: draft (against the travel), vertical (up), lateral (left)")
    axes[-1].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(png, dpi=120)
    plt.close(fig)
    return stats


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("png")
    parser.add_argument("--tool", default="sweep")
    direction = parser.add_mutually_exclusive_group()
    direction.add_argument("--scene", metavar="TOML")
    direction.add_argument("--axis", default="x", choices=["x", "-x", "y", "-y", "z", "-z"])
    parser.add_argument("--steady", nargs=2, type=float, metavar=("START", "END"))
    parser.add_argument("--entry-length", type=float, metavar="M")
    parser.add_argument("--exit-margin", type=float, metavar="M")
    parser.add_argument("--append-csv", metavar="FILE")
    parser.add_argument("--label", metavar="TEXT", help="first fields of the appended row")
    args = parser.parse_args()
    if args.append_csv and args.label is None:
        parser.error("--append-csv needs --label")
    if args.steady and (args.entry_length is not None or args.exit_margin is not None):
        parser.error("--steady gives the window; --entry-length and --exit-margin set the rule")
    return args


def window_and_directions(args, last_time):
    """((start, end), how the window was chosen, travel, up)."""
    if not args.scene:
        travel, up = axis_direction(args.axis), (0.0, 0.0, 1.0)
        window = tuple(args.steady) if args.steady else (last_time / 2, last_time)
        return window, "given" if args.steady else "the second half of the run", travel, up
    scene = load_scene(args.scene)
    tool = find_tool(scene, args.scene, args.tool)
    if args.steady:
        return tuple(args.steady), "given", tool.travel, tool.up
    window = steady_window(tool, scene, last_time, args.entry_length, args.exit_margin)
    return window, "the tool's pass through the bed", tool.travel, tool.up


def main():
    args = parse_args()
    try:
        rows = read_rows(args.csv, args.tool)
        window, how, travel, up = window_and_directions(args, float(rows[-1]["time"]))
    except (OSError, ValueError, SceneError) as error:
        sys.exit(f"plot_draft.py: {error}")
    if abs(dot(travel, up)) > 1e-9:
        sys.exit("plot_draft.py: the travel is not horizontal; draft and vertical would mix")
    time, forces = components(rows, args.tool, travel, up)
    if not any(window[0] <= t <= window[1] for t in time):
        sys.exit(f"plot_draft.py: no rows in the steady window {window[0]}..{window[1]} s")
    stats = plot(time, forces, window, args.tool, args.png)
    print(f"steady window {window[0]:.4g}–{window[1]:.4g} s ({how})")
    for name, (mean, std, count) in stats.items():
        print(f"{name} force over {window[0]:.3g}–{window[1]:.3g} s: {mean:.4g} ± {std:.3g} N "
              f"({count} rows)")
    print(f"plot: {args.png}")
    if args.append_csv:
        mean, std, _ = stats["draft"]
        with open(args.append_csv, "a") as table:
            table.write(f"{args.label},{mean:.4g},{std:.3g}\n")


if __name__ == "__main__":
    main()
