#!/usr/bin/python3
"""Checks scripts/scaling_model.py:
- its halo volume for slabs of the benchmarks' 10^6 bed equals the closed form
  G = 2 w L_y N / (L_x L_y) ghosts of 11 values (1.027e6 bytes), and every modelled halo is
  within 5 % of the measured one;
- `--validate` prints every measured point of inputs/bench/scaling_points.csv, with the model
  within 15 % of each host point and within 5 % of each single-GPU point (the ranks sharing one
  GPU are outside the model, and printed as such);
- its predictions: a CSV and a plot; efficiencies in (0, 1]; a bed that does not fit in the
  GPUs' memory (10^9 particles at 485.6 bytes each on 4 H100s) is left out; the step time of
  10^9 particles falls with every fourfold of GPUs.

Usage: check_scaling_model.py SOURCE_DIR WORK_DIR
"""
import csv
import os
import subprocess
import sys


def main():
    source, work = sys.argv[1], sys.argv[2]
    script = os.path.join(source, "scripts", "scaling_model.py")
    sys.dont_write_bytecode = True
    sys.path.insert(0, os.path.join(source, "scripts"))
    import scaling_model as model

    failures = []
    side, count, width = 1.2, 1e6, 0.007
    closed_form = 2 * width * side * count / (side * side) * 11 * 8
    _, halo = model.step_time("epyc-core", count, 2, 1, (side, side), (2, 1), "shm")
    if abs(halo - closed_form) > 1e-9 * closed_form:
        failures.append(f"slab halo {halo} bytes, closed form {closed_form}")

    out = subprocess.run([sys.executable, script, "--validate"], capture_output=True, text=True,
                         check=True).stdout
    rows = [line.split("|")[1:-1] for line in out.splitlines()[2:]]
    with open(os.path.join(source, "inputs", "bench", "scaling_points.csv")) as f:
        points = list(csv.DictReader(f))
    if len(rows) != len(points):
        failures.append(f"{len(rows)} rows printed for {len(points)} measured points")
    for point, row in zip(points, rows):
        ratio, halo_measured, halo_model = (float(row[3]), float(row[4]), float(row[5]))
        shared_gpu = point["device"].startswith("h100") and int(point["ranks_per_device"]) > 1
        limit = 0.15 if point["device"] == "epyc-core" else 0.05
        if not shared_gpu and abs(ratio - 1) > limit:
            failures.append(f"{point['label']}: model / measured {ratio}")
        if halo_measured > 0 and abs(halo_model / halo_measured - 1) > 0.05:
            failures.append(f"{point['label']}: halo {halo_model} against {halo_measured}")

    folder = os.path.join(work, "out")
    subprocess.run([sys.executable, script, "--out", folder], capture_output=True, check=True)
    if not os.path.getsize(os.path.join(folder, "scaling_model.png")):
        failures.append("empty plot")
    with open(os.path.join(folder, "scaling_model.csv")) as f:
        predicted = list(csv.DictReader(f))
    for r in predicted:
        if not 0 < float(r["efficiency"]) <= 1 + 1e-12:
            failures.append(f"efficiency {r['efficiency']} in {r}")
    for machine in model.MACHINES:
        for mode in ("gpu-aware", "staged"):
            big = [r for r in predicted if r["machine"] == machine and r["mode"] == mode and
                   r["particles"] == "1000000000"]
            device = model.DEVICES[model.MACHINES[machine]["device"]]
            smallest = min(int(r["gpus"]) for r in big)
            if 1e9 * device["bytes"] / (smallest // 4 or 1) <= 0.9 * device["memory"]:
                failures.append(f"{machine}: 10^9 would fit on {smallest // 4} GPUs")
            times = [float(r["step_seconds"]) for r in big]
            if any(b >= a for a, b in zip(times, times[1:])):
                failures.append(f"{machine} {mode}: 10^9 step times do not fall: {times}")
    for f in failures:
        print("FAILED:", f)
    if not failures:
        print(f"scaling model: {len(points)} measured points, {len(predicted)} predictions")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
