#!/usr/bin/python3
"""Strength of a cemented clod: direct tension, uniaxial compression and the Brazilian test.

    brazilian_test.py [--out DIR] [--realisations K] [--seed S] [--size mm] [--rate m/s]
                      [--shear-strength Pa] [--grain-young Pa] [--np N] [--solver PATH]

Each realisation packs spheres at random (radii uniform in 0.8-1.2 mm, packing fraction 0.58,
a periodic cube of side `--size`, grown from random points by pushing overlapping pairs apart)
and cuts specimens from that one packing (the spheres whose centres lie inside), bonded with
the cement of inputs/tillage/clods_till.toml (parallel bonds, E = 2 MPa, nu = 0.38,
sigma_c = 20 kPa, tau_c = `--shear-strength`, default 20 kPa, radius factor 1, damping 0.1;
every pair whose surfaces lie within 0.1 mm). The grains are soil (density 1850 kg/m^3) of
modulus `--grain-young` (default 20 MPa) in their contacts, which act where no bond holds:

- a bar of square section w x w (w = size/3) and length size, held at each end by a grip 2 mm
  thick (a fixed material; the top one moves at `--rate`): pulled, its direct tensile
  strength is sigma_t = F_max / w^2, F_max the largest pull of the bar on the top grip; pressed
  (the same bar, the grip moving down), its compressive strength is F_max / w^2;
- a disc of diameter D = size and thickness t = size/3, its poles cut flat over 2 alpha = 30
  degrees, between two steel platens that close at `--rate` each: its Brazilian strength is
  sigma_B = 2 P_max / (pi D t) (sin 2 alpha - alpha) / alpha, P_max the largest platen load:
  the tension at the centre of an elastic disc pressed over two opposite arcs of 2 alpha
  (Hondros 1959; 2 P / (pi D t) for line loads, ISRM 1978) when it splits.

Writes DIR/strength.csv (per realisation: the strengths, sigma_B / sigma_t, the compressive
over the tensile strength, sigma_t over the cement's sigma_c, the bar's strain at its peak and
the share of its peak pull left at the end, the fall of the disc's load after its peak, the
share of the disc's broken bonds within D/6 of the loaded diameter, and the bonds broken before
the peak with the share of them more than D/4 from the centre towards a flat),
DIR/strength.png (stress against travel, tension and Brazilian) and a line per realisation,
then the mean ratio. Each
run's folder (DIR/<seed>-bar, -column, -disc) holds its scene, particles and output; a finished
realisation (a line of strength.csv, which is replaced whole) is not run again, so a killed
study continues where it stopped; DIR/settings.json records the size, rate, shear strength and
grain modulus, and a folder of other settings is refused. Exit status 0, or 2 with a message
for bad options (before any run) or a failed run.
"""
import argparse
import csv
import json
import math
import pathlib
import subprocess
import sys

try:
    import h5py
    import numpy as np
    from scipy.spatial import cKDTree
except ImportError:
    sys.exit("brazilian_test.py needs h5py, numpy and scipy (Debian: python3-h5py, "
             "python3-numpy, python3-scipy); run it with /usr/bin/python3")

PROJECT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PROJECT / "scripts"))
from stl_file import write_binary_stl  # noqa: E402

RADIUS_MIN, RADIUS_MAX = 0.8e-3, 1.2e-3  # m
PACKING = 0.58
BOND_GAP = 0.1e-3  # m
GRIP = 2e-3  # m: thickness of each grip layer
BAR_TRAVEL = 0.02  # of the size: the grip's travel (the bar breaks near 0.7 % strain)
COLUMN_TRAVEL = 0.04  # of the size: the grip's travel when it presses the bar
DISC_TRAVEL = 0.05  # of the size: each platen's travel (the discs split at 0.015-0.04)
FLAT_HALF_ANGLE = math.radians(15)  # alpha: the disc's poles are cut flat over 2 alpha
CEMENT_STRENGTH = 2.0e4  # Pa: sigma_c, the cement's tensile strength
DRAG = 500.0  # 1/s: about a third of the critical damping of a 24 mm specimen's first mode
FIELDS = ["x", "y", "z", "r", "material"]
COLUMNS = ["seed", "particles_bar", "particles_disc", "bonds_disc", "broken_disc",
           "tensile_direct_pa", "tensile_brazilian_pa", "ratio", "direct_over_cement",
           "compressive_pa", "compressive_over_direct",
           "bar_strain_at_peak", "bar_pull_left", "disc_load_drop", "broken_central_share",
           "broken_before_peak", "before_peak_near_flats"]


def fail(message):
    print(f"brazilian_test.py: {message}", file=sys.stderr)
    sys.exit(2)


def random_packing(side, seed):
    """Centres (N x 3, in [0, side)) and radii of spheres packed at random at PACKING in a
    periodic cube: random points grown to their radii while overlapping pairs are pushed
    apart, then relaxed until no pair overlaps by more than 0.1 % of the mean radius."""
    rng = np.random.default_rng(seed)
    mean_cube = (RADIUS_MAX ** 4 - RADIUS_MIN ** 4) / (4 * (RADIUS_MAX - RADIUS_MIN))
    count = int(round(PACKING * side ** 3 / (4 / 3 * math.pi * mean_cube)))
    radius = rng.uniform(RADIUS_MIN, RADIUS_MAX, count)
    x = rng.uniform(0, side, (count, 3))
    for iteration in range(4000):
        growth = min(1.0, 0.5 + iteration / 400)
        r = radius * growth
        worst = push_apart(x, r, side)
        if growth == 1.0 and worst < 1e-3 * RADIUS_MIN:
            return x, radius
    fail(f"the packing of seed {seed} did not relax (worst overlap {worst:.3g} m)")


def push_apart(x, r, side):
    """Moves each overlapping pair apart along its centre line, each by just over half the
    overlap (periodic); returns the largest overlap found."""
    tree = cKDTree(x, boxsize=side)
    pairs = tree.query_pairs(2 * r.max(), output_type="ndarray")
    if len(pairs) == 0:
        return 0.0
    a, b = pairs[:, 0], pairs[:, 1]
    d = x[b] - x[a]
    d -= side * np.round(d / side)
    dist = np.linalg.norm(d, axis=1)
    overlap = r[a] + r[b] - dist
    hit = overlap > 0
    if not hit.any():
        return 0.0
    a, b, d, dist, overlap = a[hit], b[hit], d[hit], dist[hit], overlap[hit]
    shift = (0.55 * overlap / np.maximum(dist, 1e-12))[:, None] * d
    np.add.at(x, a, -shift)
    np.add.at(x, b, shift)
    np.mod(x, side, out=x)
    return float(overlap.max())


def bar_specimen(x, r, side):
    """The spheres of the packing whose centres lie in a bar w x w x side along z, centred in
    the cube (w = side/3): materials clod (0), low grip (1) for z below GRIP, high grip (2)
    above side - GRIP. Centres inside, so that the spheres fill the nominal section on
    average."""
    w = side / 3
    lo = (side - w) / 2
    inside = np.all((x[:, :2] >= lo) & (x[:, :2] <= lo + w), axis=1)
    material = np.where(x[:, 2] < GRIP, 1, np.where(x[:, 2] > side - GRIP, 2, 0))
    return x[inside], r[inside], material[inside]


def disc_specimen(x, r, side):
    """The spheres of the packing whose centres lie in a disc of diameter D = side and
    thickness side/3, its axis along y through the cube's centre, with its poles cut flat
    where |z - centre| > D/2 cos(FLAT_HALF_ANGLE)."""
    c = side / 2
    inside = np.hypot(x[:, 0] - c, x[:, 2] - c) <= side / 2
    inside &= np.abs(x[:, 1] - c) <= side / 6
    inside &= np.abs(x[:, 2] - c) <= side / 2 * math.cos(FLAT_HALF_ANGLE)
    return x[inside], r[inside], np.zeros(int(inside.sum()), dtype=int)


def write_particles(path, x, r, material):
    with open(path, "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(FIELDS)
        for (px, py, pz), pr, m in zip(x, r, material):
            out.writerow([f"{px:.9e}", f"{py:.9e}", f"{pz:.9e}", f"{pr:.9e}", int(m)])


def write_plate(path, centre, half):
    """A square plate of half-width `half` in the plane z = centre[2]."""
    cx, cy, cz = centre
    corners = [(cx - half, cy - half, cz), (cx + half, cy - half, cz),
               (cx + half, cy + half, cz), (cx - half, cy + half, cz)]
    a, b, c, d = corners
    write_binary_stl(path, "platen", [(a, b, c), (a, c, d)])


SCENE_HEAD = """[simulation]
end_time = {end_time}
dt = "auto"
gravity = [0.0, 0.0, 0.0]

[domain]
min = [{lo}, {lo}, {lo}]
max = [{hi}, {hi}, {hi}]

[[material]]
name = "clod"
density = 1850.0
young = {grain_young}
poisson = 0.38
restitution = 0.5
friction = 0.7
drag = {drag}
{extra_materials}
[contact]
normal = "hertz"
damping = "restitution"
tangential = "mindlin"

[neighbor]
skin = 0.2e-3

[[insert]]
csv = "particles.csv"

[output]
every = {every}
fields = ["force", "material", "id"]
bonds = true
"""

BOND = """
[[bond]]
materials = ["{a}", "{b}"]
gap = {gap}
young = 2.0e6
poisson = 0.38
tensile_strength = {cement}
shear_strength = {shear}
damping_ratio = 0.1
"""

GRIPS = """
[[material]]
name = "grip_low"
density = 1850.0
young = 2.0e6
fixed = true

[[material]]
name = "grip_high"
density = 1850.0
young = 2.0e6
fixed = true
velocity = [0.0, 0.0, {rate}]
"""

STEEL = """
[[material]]
name = "steel"
density = 7850.0
young = 2.0e8
poisson = 0.3
restitution = 0.5
friction = 0.7
"""

PLATEN = """
[[mesh]]
name = "{name}"
file = "{name}.stl"
material = "steel"

[mesh.motion]
times = [0.0, {end_time}]
velocities = [[0.0, 0.0, {v}], [0.0, 0.0, {v}]]
"""


def scene_text(kind, side, rate, travel, shear, grain_young):
    """The scene of a bar pulled ("bar") or pressed ("column") by its grips, or of a disc
    ("disc") between platens: the moving grip or each platen travels
    `travel` at `rate`; `shear` the cement's shear strength, `grain_young` the grains' modulus
    in their contacts."""
    end_time = travel / rate
    head = dict(grain_young=f"{grain_young:.6g}", end_time=f"{end_time:.6g}",
                lo=f"{-0.5 * side:.6g}", hi=f"{1.5 * side:.6g}", drag=DRAG,
                every=f"{end_time / 100:.6g}")
    cement = dict(gap=BOND_GAP, shear=shear, cement=CEMENT_STRENGTH)
    if kind in ("bar", "column"):
        pull = rate if kind == "bar" else -rate
        text = SCENE_HEAD.format(extra_materials=GRIPS.format(rate=pull), **head)
        for other in ("clod", "grip_low", "grip_high"):
            text += BOND.format(a="clod", b=other, **cement)
        return text
    text = SCENE_HEAD.format(extra_materials=STEEL, **head)
    text += BOND.format(a="clod", b="clod", **cement)
    for name, v in (("top", -rate), ("bottom", rate)):
        text += PLATEN.format(name=name, v=v, end_time=f"{end_time:.6g}")
    return text


def prepare(run_dir, kind, x, r, material, side, rate, travel, args):
    run_dir.mkdir(parents=True, exist_ok=True)
    write_particles(run_dir / "particles.csv", x, r, material)
    if kind == "disc":
        c = side / 2
        write_plate(run_dir / "top.stl", (c, c, (x[:, 2] + r).max()), 0.6 * side)
        write_plate(run_dir / "bottom.stl", (c, c, (x[:, 2] - r).min()), 0.6 * side)
    (run_dir / "scene.toml").write_text(
        scene_text(kind, side, rate, travel, args.shear_strength, args.grain_young))


def run_solver(args, run_dir):
    command = [args.solver, "scene.toml", "--output-dir", "out"]
    if args.np > 1:
        command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(args.np),
                   *command]
    with open(run_dir / "solver.log", "w") as log:
        code = subprocess.run(command, cwd=run_dir, stdout=log, stderr=subprocess.STDOUT).returncode
    if code != 0:
        tail = "".join((run_dir / "solver.log").read_text().splitlines(True)[-15:])
        fail(f"the solver failed (exit {code}) in {run_dir}:\n{tail}")


def snapshots(run_dir):
    files = sorted((run_dir / "out").glob("particles_*.h5"))
    if len(files) < 2:
        fail(f"{run_dir / 'out'} holds fewer than two snapshots")
    return files


def grip_pull(run_dir, rate):
    """(travel of the high grip [m], pull of the bar on it [N]) at each snapshot."""
    travel, pull = [], []
    for path in snapshots(run_dir):
        with h5py.File(path, "r") as f:
            held = f["material"][:] == 2
            pull.append(-float(f["force"][:, 2][held].sum()))
            travel.append(float(f.attrs["time"]) * rate)
    return np.array(travel), np.array(pull)


def platen_load(run_dir, rate):
    """(closing of the platens [m], load [N]) at each time-series row: the mean of the two
    platens' pushes."""
    with open(run_dir / "out" / "timeseries.csv") as f:
        rows = list(csv.DictReader(f))
    t = np.array([float(row["time"]) for row in rows])
    load = np.array([0.5 * (float(row["top_fz"]) - float(row["bottom_fz"])) for row in rows])
    return 2 * rate * t, load


def bond_ids(path):
    with h5py.File(path, "r") as f:
        ids = np.sort(f["bonds/ids"][:], axis=1) if "bonds/ids" in f else np.zeros((0, 2))
    return {tuple(p) for p in ids.tolist()}


def broken_bonds(run_dir):
    """(bonds at the first snapshot, the bonds of the first snapshot gone at the last)."""
    files = snapshots(run_dir)
    first, last = bond_ids(files[0]), bond_ids(files[-1])
    return first, first - last


def bond_midpoints(run_dir, bonds, side):
    """The midpoints of `bonds` (id pairs) at the first snapshot, from the disc's centre."""
    with h5py.File(snapshots(run_dir)[0], "r") as f:
        where = dict(zip(f["id"][:].tolist(), f["position"][:].tolist()))
    mid = [[0.5 * (p + q) for p, q in zip(where[a], where[b])] for a, b in bonds]
    return np.array(mid).reshape(-1, 3) - side / 2


def central_share(run_dir, broken, side):
    """The share of the broken bonds whose midpoint lies within D/6 of the loaded diameter
    (the vertical through the disc's centre): a Brazilian split runs along it."""
    if not broken:
        return 0.0
    return float(np.mean(np.abs(bond_midpoints(run_dir, broken, side)[:, 0]) < side / 6))


def broken_before(run_dir, time):
    """The bonds of the first snapshot gone at the last snapshot taken by `time`."""
    files = snapshots(run_dir)
    reached = files[0]
    for path in files:
        with h5py.File(path, "r") as f:
            if float(f.attrs["time"]) <= time:
                reached = path
    return bond_ids(files[0]) - bond_ids(reached)


def near_flats_share(run_dir, bonds, side):
    """The share of `bonds` whose midpoint lies more than D/4 from the centre along the loaded
    diameter (towards a flat, D/2 cos(alpha) away)."""
    if not bonds:
        return 0.0
    return float(np.mean(np.abs(bond_midpoints(run_dir, bonds, side)[:, 2]) > side / 4))


def realisation(args, seed):
    side = args.size * 1e-3
    x, r = random_packing(side, seed)
    base = pathlib.Path(args.out)
    bar_dir, disc_dir = base / f"{seed}-bar", base / f"{seed}-disc"
    bx, br, bm = bar_specimen(x, r, side)
    dx, dr, dm = disc_specimen(x, r, side)
    column_dir = base / f"{seed}-column"
    prepare(bar_dir, "bar", bx, br, bm, side, args.rate, BAR_TRAVEL * side, args)
    prepare(column_dir, "column", bx, br, bm, side, args.rate, COLUMN_TRAVEL * side, args)
    prepare(disc_dir, "disc", dx, dr, dm, side, args.rate, DISC_TRAVEL * side, args)
    for run_dir in (bar_dir, column_dir, disc_dir):
        run_solver(args, run_dir)
    w, d, t = side / 3, side, side / 3
    travel, pull = grip_pull(bar_dir, args.rate)
    closing, load = platen_load(disc_dir, args.rate)
    direct = pull.max() / (w * w)
    compressive = -grip_pull(column_dir, args.rate)[1].min() / (w * w)
    a = FLAT_HALF_ANGLE
    brazilian = 2 * load.max() / (math.pi * d * t) * (math.sin(2 * a) - a) / a
    made, broken = broken_bonds(disc_dir)
    peak = int(load.argmax())
    early = broken_before(disc_dir, closing[peak] / (2 * args.rate))
    return {"seed": seed, "particles_bar": len(br), "particles_disc": len(dr),
            "bonds_disc": len(made), "broken_disc": len(broken),
            "tensile_direct_pa": f"{direct:.6g}", "tensile_brazilian_pa": f"{brazilian:.6g}",
            "ratio": f"{brazilian / direct:.4f}",
            "direct_over_cement": f"{direct / CEMENT_STRENGTH:.4f}",
            "compressive_pa": f"{compressive:.6g}",
            "compressive_over_direct": f"{compressive / direct:.3f}",
            "bar_strain_at_peak": f"{travel[pull.argmax()] / (side - 2 * GRIP):.5f}",
            "bar_pull_left": f"{pull[-1] / pull.max():.3f}",
            "disc_load_drop": f"{1 - load[peak:].min() / load.max():.3f}",
            "broken_central_share": f"{central_share(disc_dir, broken, side):.3f}",
            "broken_before_peak": len(early),
            "before_peak_near_flats": f"{near_flats_share(disc_dir, early, side):.3f}"}


SETTINGS = ("size", "rate", "shear_strength", "grain_young")


def finished(out, args):
    """The rows of the realisations already in DIR/strength.csv, by seed; refuses (exit 2) a
    folder whose study was run with other settings (DIR/settings.json), and records them in a
    new one."""
    record = out / "settings.json"
    mine = {key: getattr(args, key) for key in SETTINGS}
    if record.exists():
        theirs = json.loads(record.read_text())
        for key in SETTINGS:
            if theirs.get(key) != mine[key]:
                fail(f"--{key.replace('_', '-')}: {out} holds a study run with "
                     f"{theirs.get(key)}, not {mine[key]}; give another --out")
    else:
        out.mkdir(parents=True, exist_ok=True)
        record.write_text(json.dumps(mine))
    table = out / "strength.csv"
    if not table.exists():
        return {}
    with open(table) as f:
        return {int(row["seed"]): row for row in csv.DictReader(f)}


def write_table(out, done):
    """DIR/strength.csv with the rows of `done`, replaced whole (written aside, then renamed),
    so that a kill leaves the previous table or the new one."""
    aside = out / "strength.csv.partial"
    with open(aside, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(done[s] for s in sorted(done))
    aside.replace(out / "strength.csv")


def plot(args, seeds):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    side = args.size * 1e-3
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for seed in seeds:
        base = pathlib.Path(args.out)
        travel, pull = grip_pull(base / f"{seed}-bar", args.rate)
        ax[0].plot(travel * 1e3, pull / (side / 3) ** 2 / 1e3, label=f"seed {seed}")
        closing, load = platen_load(base / f"{seed}-disc", args.rate)
        ax[1].plot(closing * 1e3, 2 * load / (math.pi * side * side / 3) / 1e3,
                   label=f"seed {seed}")
    ax[0].set(xlabel="grip travel [mm]", ylabel="F / w² [kPa]", title="direct tension")
    ax[1].set(xlabel="platen closing [mm]", ylabel="2P / (π D t) [kPa]", title="Brazilian")
    for a in ax:
        a.legend()
        a.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(pathlib.Path(args.out) / "strength.png", dpi=120)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="brazilian")
    parser.add_argument("--realisations", type=int, default=3)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--size", type=float, default=24.0, help="disc diameter D [mm]")
    parser.add_argument("--rate", type=float, default=0.01, help="platen and grip speed [m/s]")
    parser.add_argument("--shear-strength", type=float, default=2e4,
                        help="the cement's shear strength tau_c [Pa]")
    parser.add_argument("--grain-young", type=float, default=2e7,
                        help="the grains' Young's modulus in their contacts [Pa]")
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--solver", default=str(PROJECT / "build/gpudem-mpi"))
    args = parser.parse_args()
    if args.realisations < 1:
        fail("--realisations: give at least 1")
    if args.seed < 0:
        fail("--seed: give an integer >= 0")
    if not 24 <= args.size <= 200:
        fail("--size: give a diameter from 24 to 200 mm (at least 4 grains across the bar)")
    if not 0 < args.rate < math.inf:
        fail("--rate: give a speed > 0")
    if not (0 < args.shear_strength < math.inf and 0 < args.grain_young < math.inf):
        fail("--shear-strength and --grain-young: give values > 0")
    if args.np < 1:
        fail("--np: give at least 1 rank")
    if not pathlib.Path(args.solver).is_file():
        fail(f"--solver: {args.solver} does not exist")
    out = pathlib.Path(args.out)
    done = finished(out, args)
    seeds = range(args.seed, args.seed + args.realisations)
    for seed in seeds:
        if seed not in done:
            done[seed] = realisation(args, seed)
            write_table(out, done)
        row = done[seed]
        print(f"seed {seed}: direct {float(row['tensile_direct_pa']) / 1e3:.2f} kPa, "
              f"Brazilian {float(row['tensile_brazilian_pa']) / 1e3:.2f} kPa, "
              f"ratio {row['ratio']}, {row['broken_disc']} of {row['bonds_disc']} bonds broken, "
              f"{float(row['broken_central_share']) * 100:.0f} % near the loaded diameter",
              flush=True)
    ratios = [float(done[s]["ratio"]) for s in seeds]
    print(f"mean ratio sigma_B / sigma_t = {np.mean(ratios):.3f} "
          f"(range {min(ratios):.3f}-{max(ratios):.3f}, {len(ratios)} realisations)")
    plot(args, seeds)


if __name__ == "__main__":
    main()
