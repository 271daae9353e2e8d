#!/usr/bin/env bash
# Angle of repose of moist grains: the lifting-cylinder heap of inputs/heap/ with JKR adhesion
# of surface energy gamma between the grains (grain-steel pairs take the mixing rule's mean with
# the steel's 0). The fill is poured and settled dry once (inputs/heap/heap_fill.toml); each
# gamma lifts the cylinder from that same fill (inputs/heap/heap_lift.toml with
# contact.cohesion = "jkr") and scripts/repose_angle.py measures the heap. Prints one line per
# gamma: the granular Bond number Bo = (3/2 pi gamma R*) / (m g) of two mean grains (R* = R/2),
# the lift's wall time and the angle. A finished gamma (its angle file) is not run again.
# Usage: scripts/heap_cohesion.sh [OUT (default out/heap-cohesion)]
#   GAMMAS  surface energies in J/m^2 (default "0 0.05 0.1 0.2")
#   NP      OpenMP threads (default 2); BUILD_DIR as for setup.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
OUT=${1:-out/heap-cohesion}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
NP=${NP:-2}
BUILD=${BUILD_DIR:-build}
GAMMAS=${GAMMAS:-0 0.05 0.1 0.2}
mkdir -p "$OUT"
if [[ ! -f "$OUT/fill/bed.h5" ]]; then
  OMP_NUM_THREADS=$NP "$BUILD"/gpudem-mpi --quiet inputs/heap/heap_fill.toml \
    --output-dir "$OUT/fill"
fi
for gamma in $GAMMAS; do
  run="$OUT/gamma_$gamma"
  if [[ ! -f "$run/angle.txt" ]]; then
    rm -rf "$run"
    start=$SECONDS
    OMP_NUM_THREADS=$NP "$BUILD"/gpudem-mpi --quiet inputs/heap/heap_lift.toml \
      --output-dir "$run" --set "insert.0.bed=\"$OUT/fill/bed.h5\"" \
      --set 'contact.cohesion="jkr"' --set "material.0.surface_energy=$gamma"
    echo "$((SECONDS - start))" > "$run/wall_seconds.txt"
    last=$(ls "$run"/particles_*.h5 | sort | tail -n 1)
    /usr/bin/python3 scripts/repose_angle.py "$last" > "$run/angle.tmp"
    mv "$run/angle.tmp" "$run/angle.txt"
  fi
  bond=$(/usr/bin/python3 -c "
import math
r, rho, g = 0.002, 2500.0, 9.81
print(f'{1.5 * math.pi * $gamma * r / 2 / (4 / 3 * math.pi * r**3 * rho * g):.3g}')")
  echo "gamma $gamma J/m^2  Bo $bond  lift $(cat "$run/wall_seconds.txt") s  $(head -n 1 "$run/angle.txt"); $(tail -n 1 "$run/angle.txt")"
done
