#!/usr/bin/env bash
# Draft against Young's modulus two ways, at the tillage quickstart's scale
# (inputs/tillage/quickstart_*.toml): every pass from the one bed settled at E = 2 MPa (as
# scripts/cultivator_trends.sh does), and every pass from a bed settled at its own E. The
# difference tells how much of the E trend comes from the bed's packing rather than from the
# pass. Writes young_beds.csv (E, bed, draft mean and std over 0.45-0.84 s).
# Usage: scripts/young_beds.sh [OUT (default out/young-beds)]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
OUT=${1:-out/young-beds}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
NP=${NP:-1}
run() { mpirun -np "$NP" --bind-to none build/gpudem-mpi --quiet "$@"; }
bed() {  # E: settles and trims a bed at modulus E
  run inputs/tillage/quickstart_bed.toml --output-dir "$OUT/bed-$1" --set "material.0.young=$1"
}
pass() {  # E BED_E: the sweep pass at modulus E from the bed settled at BED_E
  local dir="$OUT/pass-$1-bed-$2"
  run inputs/tillage/quickstart_till.toml --output-dir "$dir" --set "material.0.young=$1" \
    --set "insert.0.bed=\"$OUT/bed-$2/bed.h5\""
  local line
  line=$(/usr/bin/python3 scripts/plot_draft.py "$dir/timeseries.csv" "$dir/draft.png" \
    --tool sweep --axis x --steady 0.45 0.84)
  echo "E = $1, bed at $2: $line"
  /usr/bin/python3 - "$line" "$1" "$2" >> "$OUT/young_beds.csv" <<'PY'
import re, sys
mean, std = re.search(r": ([-0-9.e+]+) ± ([-0-9.e+]+) N", sys.argv[1]).groups()
print(f"{sys.argv[2]},{sys.argv[3]},{mean},{std}")
PY
}
mkdir -p "$OUT"
echo "young_Pa,bed_young_Pa,draft_mean_N,draft_std_N" > "$OUT/young_beds.csv"
for E in 1e6 2e6 4e6 8e6; do bed "$E"; done
for E in 1e6 2e6 4e6 8e6; do
  pass "$E" 2e6
  [[ $E = 2e6 ]] || pass "$E" "$E"
done
