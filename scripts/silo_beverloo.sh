#!/usr/bin/env bash
# Silo discharge against Beverloo's law: the bed of inputs/silo/silo_fill.toml (about 25,000
# spheres of R = 2 ± 0.2 mm settled 0.1 m deep in a 0.12 m square silo) drains through round
# orifices of several diameters (inputs/silo/silo_discharge.toml with a floor plate from
# scripts/make_orifice_stl.py for each); scripts/beverloo_fit.py fits W = C ρ_b √g (D − k d)^{5/2}
# to the discharge rates and says whether C and k agree with the literature (exit status 1 if
# not). Writes beverloo.csv and beverloo.png under OUT; with fewer than four diameters it
# prints the discharge rates only.
# Usage: scripts/silo_beverloo.sh [OUT (default out/silo)]
#   DIAMETERS  orifice diameters in m (default "0.024 0.028 0.032 0.036 0.040": 6 to 10 grains)
#   SET        scene overrides for both stages, e.g. "material.0.young=2e7 simulation.dt=1e-5"
#   SIDE       silo side in m (default 0.12); the fill's count scales with its area
#              (30,000 grains at 0.12 m), so the bed keeps its 0.1 m depth
#   NP         ranks (default 1); BUILD_DIR as for setup.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
OUT=${1:-out/silo}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
NP=${NP:-1}
DIAMETERS=${DIAMETERS:-"0.024 0.028 0.032 0.036 0.040"}
SIDE=${SIDE:-0.12}
share_cores "$NP"
overrides=(--set "domain.max=[$SIDE, $SIDE, 0.25]" --set "wall.1.point=[$SIDE, 0.0, 0.0]"
           --set "wall.3.point=[0.0, $SIDE, 0.0]")
for item in ${SET:-}; do overrides+=(--set "$item"); done
count=$(awk -v s="$SIDE" 'BEGIN { printf "%d", 30000 * (s / 0.12) ^ 2 + 0.5 }')
run() {  # SCENE DIR [--set ...]: one stage, timed
  local scene=$1 dir=$2
  shift 2
  local start=$SECONDS
  mpirun -np "$NP" --bind-to none "${BUILD_DIR:-build}"/gpudem-mpi --quiet "$scene" \
    --output-dir "$dir" "${overrides[@]}" "$@"
  echo "$(basename "$dir"): $((SECONDS - start)) s"
}
mkdir -p "$OUT"
run inputs/silo/silo_fill.toml "$OUT/fill" --set "insert.0.count=$count" \
  --set "insert.0.region.max=[$SIDE, $SIDE, 0.25]"
runs=()
for D in $DIAMETERS; do
  dir="$OUT/orifice-$D"
  mkdir -p "$dir"
  /usr/bin/python3 scripts/make_orifice_stl.py "$dir/orifice.stl" --side "$SIDE" --diameter "$D"
  run inputs/silo/silo_discharge.toml "$dir" --set "insert.0.bed=\"$OUT/fill/bed.h5\"" \
    --set "mesh.0.file=\"$dir/orifice.stl\""
  runs+=("$D=$dir")
done
/usr/bin/python3 scripts/beverloo_fit.py "$OUT/fill/bed.h5" "${runs[@]}" \
  --csv "$OUT/beverloo.csv" --png "$OUT/beverloo.png"
