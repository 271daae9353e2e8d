#!/usr/bin/env bash
# The tillage quickstart (inputs/tillage/quickstart_*.toml) in the double, mixed and float
# precision policies: a bed settled in each, and the sweep pass in each from the double bed and
# from its own bed. Prints the wall time of every stage and each pass's draft (mean and standard
# deviation over 0.45-0.84 s, plot_draft.py); writes precision.csv and each pass's draft.png.
# Usage: scripts/precision_draft.sh [OUT]   (NP=ranks, default 1; BUILD_DIR as for setup.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
OUT=${1:-out/precision-draft}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
NP=${NP:-1}
share_cores "$NP"
run() {  # PRECISION SCENE DIR [--set ...]: one stage, timed
  local precision=$1 scene=$2 dir=$3
  shift 3
  local start=$SECONDS
  mpirun -np "$NP" --bind-to none "${BUILD_DIR:-build}"/gpudem-mpi --quiet "$scene" --output-dir "$dir" \
    --set "simulation.precision=\"$precision\"" "$@"
  echo "$(basename "$dir"): $((SECONDS - start)) s"
}
mkdir -p "$OUT"
echo "precision,bed,draft_mean_N,draft_std_N" > "$OUT/precision.csv"
for precision in double mixed float; do
  run "$precision" inputs/tillage/quickstart_bed.toml "$OUT/bed-$precision"
done
for precision in double mixed float; do
  beds=double
  [[ $precision = double ]] || beds="double $precision"
  for bed in $beds; do
    dir="$OUT/pass-$precision-bed-$bed"
    run "$precision" inputs/tillage/quickstart_till.toml "$dir" \
      --set "insert.0.bed=\"$OUT/bed-$bed/bed.h5\""
    echo -n "$precision pass, $bed bed: "
    /usr/bin/python3 scripts/plot_draft.py "$dir/timeseries.csv" "$dir/draft.png" \
      --tool sweep --axis x --steady 0.45 0.84 --append-csv "$OUT/precision.csv" \
      --label "$precision,$bed"
  done
done
