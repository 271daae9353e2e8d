#!/usr/bin/python3
"""Step time and parallel efficiency of gpudem-mpi from 1 to 4,096 GPUs, from measured figures.

The model (docs/performance.md, "Scaling model"): a rank owns a block of the bed and steps its
N_r particles in t_dev(N_r) = t0 + N_r / R, the device's fixed cost per step and its throughput,
both fitted to single-device runs. Per step it refreshes its ghosts: the particles within the
ghost width w of its block's faces, 11 values of 8 bytes each, one message per neighbouring
rank, at the link's latency and bandwidth (staged runs copy the halo through host memory both
ways). The code overlaps that refresh with the forces of the rows that read no ghost, so

    t_step = t_c (1 - f) + max(t_c f (1 - b), t_halo) + t_c f b + t_reduce

with f the forces' share of the step, b the share of rows within w of a cut face, and
t_reduce two tree reductions a step. Ranks that share a device take turns on it (their t_c
add up). `--validate` prints the model beside every measured point of
inputs/bench/scaling_points.csv; the default prints and plots the predictions.

Usage: scripts/scaling_model.py [--validate] [--out DIR] [--mode gpu-aware|staged|both]
"""
import argparse
import csv
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
POINTS = os.path.join(ROOT, "inputs", "bench", "scaling_points.csv")
VALUES_PER_GHOST = 11  # position, radius, velocity, inverse mass, spin
REDUCTIONS_PER_STEP = 2  # the rebuild test and the health check

# Devices: fixed cost per step t0 [s], throughput R [particle-steps/s], the forces' share of
# the step, bytes per particle, memory [bytes]. h100-*: fitted to the runs of
# performance.md (t0 from the soil beds' step at 10^5); a100: unmeasured, R scaled by the
# memory bandwidth of an A100 40GB against an H100 SXM (1.56 / 3.35 TB/s, NVIDIA datasheets).
DEVICES = {
    "epyc-core": dict(t0=0.0, rate=1e6 / 0.468, forces=0.97, bytes=548.4, memory=24e9),
    "h100-double-hooke": dict(t0=5e-5, rate=1e6 / (1.856e-3 - 5e-5), forces=0.72,
                              bytes=739.3, memory=80e9),
    "h100-mixed-soil": dict(t0=5e-5, rate=1.32e9, forces=0.764, bytes=485.6, memory=80e9),
    "a100-mixed-soil": dict(t0=5e-5, rate=1.32e9 * 1.56 / 3.35, forces=0.764, bytes=485.6,
                            memory=40e9),
}

# Links: latency [s] and bandwidth [bytes/s]. shm: ranks of one node through shared memory;
# pcie: a staged halo's copy each way; the networks as their vendors rate them (Slingshot
# 200 Gb/s, InfiniBand NDR 400 Gb/s), NVLink 4 at 450 GB/s a direction.
LINKS = {
    "shm": (1e-6, 5e9),
    "pcie4": (1e-5, 25e9),
    "pcie5": (1e-5, 50e9),
    "nvlink4": (2e-6, 450e9),
    "slingshot200": (2e-6, 25e9),
    "ndr400": (1.5e-6, 50e9),
}

# Machines: device, GPUs per node, link within a node (GPU-aware), network, NICs per node,
# host copy link of a staged halo.
MACHINES = {
    "komondor-a100": dict(device="a100-mixed-soil", per_node=4, intra="pcie4",
                          network="slingshot200", nics=1, staging="pcie4"),
    "h100-cluster": dict(device="h100-mixed-soil", per_node=4, intra="nvlink4",
                         network="ndr400", nics=4, staging="pcie5"),
}

# The predicted beds: spheres of the benchmarks' soil bed (r = 2.5 +- 0.5 mm), 6.94e5 per m^2
# of bed, ghost width 7 mm, on a square bed cut into a grid of columns.
BED_PER_AREA = 1e6 / 1.44
GHOST_WIDTH = 0.007


def device_time(device, particles):
    d = DEVICES[device]
    return d["t0"] + particles / d["rate"]


def grid(ranks):
    """The most square dims_x x dims_y = ranks."""
    x = int(math.sqrt(ranks))
    while ranks % x:
        x -= 1
    return ranks // x, x


def neighbours(dims):
    return max(1, min(dims[0], 3) * min(dims[1], 3) - 1) if dims[0] * dims[1] > 1 else 0


def block_shares(side, dims, width):
    """Ghosts per owned particle, and the share of owned rows within `width` of a cut face."""
    lx, ly = side[0] / dims[0], side[1] / dims[1]
    cx, cy = (dims[0] > 1), (dims[1] > 1)
    area = lx * ly
    halo = (lx + 2 * width * cx) * (ly + 2 * width * cy) - area
    inner = max(0.0, lx - 2 * width * cx) * max(0.0, ly - 2 * width * cy)
    return halo / area, 1 - inner / area


def halo_time(bytes_out, messages, link, staging=None):
    latency, bandwidth = LINKS[link]
    t = messages * latency + bytes_out / bandwidth
    if staging:
        copy_latency, copy_bandwidth = LINKS[staging]
        t += 2 * (copy_latency + bytes_out / copy_bandwidth)
    return t


def step_time(device, particles, ranks, per_device, side, dims, link, staging=None,
              reduce_latency=1e-6):
    """Modelled step time [s] and its halo bytes per rank."""
    owned = particles / ranks
    t_c = per_device * device_time(device, owned)
    if ranks == 1:
        return t_c, 0.0
    ghosts_per_owned, boundary = block_shares(side, dims, GHOST_WIDTH)
    halo_bytes = ghosts_per_owned * owned * VALUES_PER_GHOST * 8
    t_halo = halo_time(halo_bytes, neighbours(dims), link, staging)
    f = DEVICES[device]["forces"]
    t_reduce = REDUCTIONS_PER_STEP * reduce_latency * math.ceil(math.log2(ranks))
    t = t_c * (1 - f) + max(t_c * f * (1 - boundary), t_halo) + t_c * f * boundary + t_reduce
    return t, halo_bytes


def read_points(path=POINTS):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def validate(points):
    """Model against every measured point: rows of (label, measured, model, ratio, halo)."""
    rows = []
    for p in points:
        ranks, per_device = int(p["ranks"]), int(p["ranks_per_device"])
        staged = p["device"].startswith("h100")  # the measured GPU halos went through the host
        model, halo = step_time(p["device"], float(p["particles"]), ranks, per_device,
                                (float(p["side_x"]), float(p["side_y"])),
                                (int(p["dims_x"]), int(p["dims_y"])), "shm",
                                "pcie5" if staged else None)
        measured = float(p["step_seconds"])
        rows.append((p["label"], measured, model, model / measured, float(p["halo_bytes"]), halo))
    return rows


def predict(machine, particles, gpus, gpu_aware):
    """(step time [s], halo bytes) on `gpus` GPUs of `machine`, or None when it does not fit."""
    m = MACHINES[machine]
    d = DEVICES[m["device"]]
    if particles / gpus * d["bytes"] > 0.9 * d["memory"]:
        return None
    side = math.sqrt(particles / BED_PER_AREA)
    dims = grid(gpus)
    inter_node = gpus > m["per_node"]
    link = m["network"] if inter_node else m["intra"]
    t, halo = step_time(m["device"], particles, gpus, 1, (side, side), dims, link,
                        None if gpu_aware else m["staging"],
                        LINKS[m["network"]][0] if inter_node else 1e-6)
    if inter_node and m["nics"] < m["per_node"]:  # the node's GPUs share its NICs
        t += (m["per_node"] / m["nics"] - 1) * halo / LINKS[link][1]
    return t, halo


def predictions(modes):
    rows = []
    for machine in MACHINES:
        for gpu_aware in modes:
            for particles in (1e7, 1e8, 1e9):
                base = None
                for gpus in [4 ** k for k in range(7)]:
                    result = predict(machine, particles, gpus, gpu_aware)
                    if result is None:
                        continue
                    t, halo = result
                    base = base or (gpus, t)
                    efficiency = base[1] * base[0] / (t * gpus)
                    rows.append(dict(machine=machine, mode="gpu-aware" if gpu_aware else "staged",
                                     particles=int(particles), gpus=gpus, step_seconds=t,
                                     particle_steps_per_s=particles / t,
                                     efficiency=efficiency, halo_bytes=halo))
    return rows


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    keys = sorted({(r["machine"], r["mode"], r["particles"]) for r in rows})
    for machine, mode, particles in keys:
        sel = [r for r in rows if (r["machine"], r["mode"], r["particles"]) ==
               (machine, mode, particles)]
        ax.plot([r["gpus"] for r in sel], [r["efficiency"] for r in sel], marker="o",
                linestyle="-" if mode == "gpu-aware" else "--",
                label=f"{machine} {mode} {particles:.0e}")
    ax.set_xscale("log", base=2)
    ax.set_xlabel("GPUs")
    ax.set_ylabel("parallel efficiency (vs fewest GPUs that fit)")
    ax.set_ylim(0, 1.05)
    ax.legend(fontsize=6, ncol=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--validate", action="store_true",
                        help="print the model beside the measured points and stop")
    parser.add_argument("--out", default="out/scaling_model", help="folder of the CSV and plot")
    parser.add_argument("--mode", choices=("gpu-aware", "staged", "both"), default="both")
    args = parser.parse_args(argv)
    if args.validate:
        print("| point | measured step [s] | model [s] | model / measured | halo measured | model |")
        print("|---|---|---|---|---|---|")
        for label, measured, model, ratio, halo, halo_model in validate(read_points()):
            print(f"| {label} | {measured:.4g} | {model:.4g} | {ratio:.2f} | {halo:.4g} "
                  f"| {halo_model:.4g} |")
        return 0
    modes = {"gpu-aware": [True], "staged": [False], "both": [True, False]}[args.mode]
    rows = predictions(modes)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "scaling_model.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print("| machine | halo | particles | GPUs | step [ms] | particle-steps/s | efficiency |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['machine']} | {r['mode']} | {r['particles']:.0e} | {r['gpus']} "
              f"| {1e3 * r['step_seconds']:.3g} | {r['particle_steps_per_s']:.3g} "
              f"| {r['efficiency']:.2f} |")
    plot(rows, os.path.join(args.out, "scaling_model.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
