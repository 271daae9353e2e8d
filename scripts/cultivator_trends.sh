#!/usr/bin/env bash
# Draft-force trends of the cultivator study: the sweep pass of inputs/tillage/cultivator_till.toml
# repeated from the uncalibrated bed of scripts/cultivator_study.sh with one soil parameter
# changed at a time (density, restitution, Young's modulus, friction with μ_s = μ_d). Every run
# starts from the same bed, so only the pass sees the change. Writes trends.csv and one plot per
# parameter (scripts/plot_trends.py).
# Usage: scripts/cultivator_trends.sh [OUT (default out/cultivator)]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
OUT=${1:-out/cultivator}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
BED="$OUT/uncalibrated/bed/bed.h5"
[[ -f $BED ]] || { echo "no bed at $BED: run scripts/cultivator_study.sh first" >&2; exit 1; }
NP=${NP:-1}
share_cores "$NP"
echo "parameter,value,draft_mean_N,draft_std_N" > "$OUT/trends.csv"
pass() {  # parameter value --set options...
  local name=$1 value=$2
  shift 2
  local dir="$OUT/trends/$name-$value"
  mpirun -np "$NP" --bind-to none build/gpudem-mpi --quiet inputs/tillage/cultivator_till.toml \
    --output-dir "$dir" --set "insert.0.bed=\"$BED\"" "$@"
  echo -n "$name $value: "
  /usr/bin/python3 scripts/plot_draft.py "$dir/timeseries.csv" "$dir/draft.png" \
    --tool sweep --axis x --steady 0.45 0.84 --append-csv "$OUT/trends.csv" --label "$name,$value"
}
for rho in 1500 1850 2200; do pass density "$rho" --set "material.0.density=$rho"; done
for e in 0.2 0.5 0.8; do pass restitution "$e" --set "material.0.restitution=$e"; done
for E in 1e6 2e6 4e6 8e6; do pass young "$E" --set "material.0.young=$E"; done
for mu in 0.4 0.6 0.8; do
  pass friction "$mu" --set "material.0.friction=$mu" --set "material.0.friction_dynamic=$mu"
done
/usr/bin/python3 scripts/plot_trends.py "$OUT/trends.csv" "$OUT"
