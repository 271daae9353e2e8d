#!/usr/bin/env bash
# A draft-force trend two ways, at the tillage quickstart's scale (inputs/tillage/quickstart_*.toml):
# every pass cutting the one bed settled with the base value of a soil parameter (as
# scripts/cultivator_trends.sh does), and every pass cutting a bed settled with its own value.
# The difference tells how much of the trend comes from the bed's packing rather than from the
# pass. Writes trend.csv (value, value the bed was settled with, draft mean and std over
# 0.45-0.84 s) and each pass's draft.png.
# Usage: scripts/own_bed_trend.sh KEY BASE "VALUES" [OUT]
#   e.g. scripts/own_bed_trend.sh material.0.young 2e6 "1e6 2e6 4e6 8e6" out/young-beds
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
KEY=$1
BASE=$2
read -r -a VALUES <<< "$3"
OUT=${4:-out/own-bed-trend}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
NP=${NP:-1}
share_cores "$NP"
run() { mpirun -np "$NP" --bind-to none build/gpudem-mpi --quiet "$@"; }
bed() {  # VALUE: settles and trims a bed with KEY = VALUE
  run inputs/tillage/quickstart_bed.toml --output-dir "$OUT/bed-$1" --set "$KEY=$1"
}
pass() {  # VALUE BED_VALUE: the sweep pass with KEY = VALUE from the bed settled with BED_VALUE
  local dir="$OUT/pass-$1-bed-$2"
  run inputs/tillage/quickstart_till.toml --output-dir "$dir" --set "$KEY=$1" \
    --set "insert.0.bed=\"$OUT/bed-$2/bed.h5\""
  echo -n "$KEY = $1, bed at $2: "
  /usr/bin/python3 scripts/plot_draft.py "$dir/timeseries.csv" "$dir/draft.png" \
    --tool sweep --axis x --steady 0.45 0.84 --append-csv "$OUT/trend.csv" --label "$1,$2"
}
mkdir -p "$OUT"
echo "value,bed_value,draft_mean_N,draft_std_N" > "$OUT/trend.csv"
for value in "${VALUES[@]}"; do bed "$value"; done
for value in "${VALUES[@]}"; do
  pass "$value" "$BASE"
  [[ $value = "$BASE" ]] || pass "$value" "$value"
done
