#!/usr/bin/env bash
# Cost of a finely tessellated tool: the quickstart pass (inputs/tillage/quickstart_till.toml,
# the sweep at 0.08 m depth and 0.7 m/s through about 13,000 spheres) to t = END (default 0.5 s,
# the sweep wholly in the bed from 0.41 s) with the same sweep split into 32 N^2 triangles
# (scripts/make_sweep_stl.py --subdivide N) for N = 2 ... 40 (128 to 51,200 triangles), ROUNDS
# rounds with the sizes interleaved. One rank with OMP_NUM_THREADS threads (default 2).
# Appends to OUT/results.csv (triangles, round, wall time, force and neighbour-list time, peak
# resident memory, the steady draft over 0.41 s to END); a size and round already there is not
# run again, so a killed benchmark continues where it stopped. The bed is BED, or stage 1 of
# the quickstart made into OUT/bed when BED is not given.
# Usage: scripts/bench_mesh_triangles.sh [OUT]   (default out/bench-mesh-triangles)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
OUT=${1:-out/bench-mesh-triangles}
END=${END:-0.5}
ROUNDS=${ROUNDS:-2}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
BED=${BED:-$OUT/bed/bed.h5}
if [[ ! -f $BED ]]; then
  build/gpudem-mpi inputs/tillage/quickstart_bed.toml --output-dir "$OUT/bed" --quiet \
    --set output.every=10.0
fi
results="$OUT/results.csv"
header="triangles,round,wall_s,forces_s,lists_s,peak_rss_mib,draft_n"
[[ -f $results ]] || echo "$header" > "$results"
for round in $(seq 1 "$ROUNDS"); do
  for n in 2 4 8 16 25 40; do
    triangles=$((32 * n * n))
    grep -q "^$triangles,$round," "$results" && continue
    stl="$OUT/sweep_$triangles.stl"
    [[ -f $stl ]] || /usr/bin/python3 scripts/make_sweep_stl.py "$stl" --subdivide "$n" > /dev/null
    run="$OUT/run_$triangles"
    rm -rf "$run"
    /usr/bin/time -f "peak_rss_kib %M" -o "$OUT/time.txt" build/gpudem-mpi \
      inputs/tillage/quickstart_till.toml --output-dir "$run" --backend host \
      --set "insert.0.bed=\"$BED\"" --set "mesh.0.file=\"$stl\"" \
      --set "simulation.end_time=$END" --set output.every=10.0 > "$OUT/log_$triangles.txt"
    /usr/bin/python3 - "$OUT/log_$triangles.txt" "$OUT/time.txt" "$run/timeseries.csv" \
      "$triangles" "$round" >> "$results" <<'PY'
import csv, re, statistics, sys
log, timing, series, triangles, round_ = sys.argv[1:]
text = open(log).read()
wall = re.search(r"steps in ([0-9.]+) s", text).group(1)
forces = re.search(r"forces ([0-9.]+) s", text).group(1)
lists = re.search(r"neighbour lists ([0-9.]+) s", text).group(1)
rss = int(re.search(r"peak_rss_kib (\d+)", open(timing).read()).group(1)) / 1024
with open(series) as f:
    draft = [-float(r["sweep_fx"]) for r in csv.DictReader(f) if float(r["time"]) >= 0.41]
print(f"{triangles},{round_},{wall},{forces},{lists},{rss:.0f},{statistics.mean(draft):.2f}")
PY
    tail -1 "$results"
  done
done
