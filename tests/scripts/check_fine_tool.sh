#!/usr/bin/env bash
# A scanned tool's tessellation: the quickstart pass (inputs/tillage/quickstart_*.toml: a bed of
# about 13,000 spheres of radius 8.5 mm, the sweep at 0.08 m depth and 0.7 m/s) cut once with the
# shipped 32-triangle sweep and once with the same surface split into 20,000 triangles
# (scripts/make_sweep_stl.py --subdivide 25, blade edges of 10.5 mm and less, so a sphere on
# the blade is within reach of tens of triangles at once). The fine pass must run to its end and
# its steady draft (−F_x over 0.45–0.84 s, the tool wholly in the bed) must agree with the coarse
# one within the coarse draft's fluctuation (its standard deviation over that window).
# Usage: check_fine_tool.sh SOURCE_DIR GPUDEM_BINARY WORK_DIR
set -euo pipefail
source_dir=$1
binary=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
scenes="$source_dir/inputs/tillage"
/usr/bin/python3 "$source_dir/scripts/make_sweep_stl.py" "$work/sweep_fine.stl" --subdivide 25
run() { "$binary" "$@" --backend host --quiet --set output.every=1.0; }
run "$scenes/quickstart_bed.toml" --output-dir "$work/bed"
for tool in coarse fine; do
  mesh="$scenes/sweep.stl"
  [[ $tool == fine ]] && mesh="$work/sweep_fine.stl"
  run "$scenes/quickstart_till.toml" --output-dir "$work/$tool" \
    --set "insert.0.bed=\"$work/bed/bed.h5\"" --set "mesh.0.file=\"$mesh\""
done
/usr/bin/python3 - "$work/coarse/timeseries.csv" "$work/fine/timeseries.csv" <<'PY'
import csv
import statistics
import sys

def steady_draft(path):
    with open(path) as f:
        rows = [r for r in csv.DictReader(f) if 0.45 <= float(r["time"]) <= 0.84]
    draft = [-float(r["sweep_fx"]) for r in rows]
    return statistics.mean(draft), statistics.stdev(draft), len(draft)

(coarse, spread, n), (fine, fine_spread, _) = steady_draft(sys.argv[1]), steady_draft(sys.argv[2])
print(f"steady draft over {n} rows: coarse {coarse:.2f} ± {spread:.2f} N, "
      f"fine {fine:.2f} ± {fine_spread:.2f} N")
if coarse < 20 or abs(fine - coarse) > spread:
    sys.exit("FAIL: the fine tool's draft is not the coarse one's within its fluctuation")
PY
