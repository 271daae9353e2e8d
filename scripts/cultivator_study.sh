#!/usr/bin/env bash
# The cultivator study: the soil bed and sweep pass of inputs/tillage/cultivator_{bed,till}.toml
# with the uncalibrated soil set and with the calibrated set of the GPU DEM tillage thesis, each
# with its own bed; prints the draft force over the steady window and writes draft plots.
# Usage: scripts/cultivator_study.sh [OUT (default out/cultivator)]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
OUT=${1:-out/cultivator}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
NP=${NP:-1}
share_cores "$NP"
calibrated=(--set material.0.density=2387 --set material.0.young=7.978e6
            --set material.0.poisson=0.486 --set material.0.restitution=0.113
            --set material.0.friction=0.495 --set material.0.friction_dynamic=0.495
            --set material.0.rolling_friction=0.264)
run() { mpirun -np "$NP" --bind-to none build/gpudem-mpi --quiet "$@"; }
for set in uncalibrated calibrated; do
  extra=()
  [[ $set = calibrated ]] && extra=("${calibrated[@]}")
  run inputs/tillage/cultivator_bed.toml --output-dir "$OUT/$set/bed" "${extra[@]}"
  run inputs/tillage/cultivator_till.toml --output-dir "$OUT/$set/till" "${extra[@]}" \
    --set "insert.0.bed=\"$OUT/$set/bed/bed.h5\""
  echo -n "$set: "
  /usr/bin/python3 scripts/plot_draft.py "$OUT/$set/till/timeseries.csv" "$OUT/$set/draft.png" \
    --tool sweep --axis x --steady 0.45 0.84
done
