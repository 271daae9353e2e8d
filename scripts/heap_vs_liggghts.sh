#!/usr/bin/env bash
# Angle of repose by the lifting-cylinder test, side by side on one machine: gpudem-mpi
# (inputs/heap/heap_fill.toml) fills the cylinder and lets the fill settle, then both it
# (inputs/heap/heap_lift.toml) and LIGGGHTS (Debian's liggghts, inputs/bench/liggghts_heap.in)
# lift the cylinder away from that same fill, with the same floor, cylinder, materials,
# Hertz-Mindlin, constant rolling torque, time step and skin; scripts/repose_angle.py measures
# both heaps. Prints each lift's wall time and each heap's angle. Installs liggghts when missing.
# Usage: scripts/heap_vs_liggghts.sh [OUT (default out/heap-liggghts)]
#   ROLLING  rolling friction mu_r of grains and steel in both codes (default 0.1, the scenes')
#   SET      further overrides for gpudem-mpi's stages (LIGGGHTS keeps its input's values)
#   NP       cores for each code (default 2); BUILD_DIR as for setup.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh liggghts > /dev/null
source scripts/mpi-env.sh
OUT=${1:-out/heap-liggghts}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
NP=${NP:-2}
BUILD=${BUILD_DIR:-build}
DT=4.4e-5      # both codes' lift step (gpudem-mpi's "auto" at dt_fraction 0.2)
LIFT=56818     # 2.5 s of lifting at 50 mm/s
REST=22727     # then 1 s at rest
ROLLING=${ROLLING:-0.1}
overrides=(--set "material.0.rolling_friction=$ROLLING"
           --set "material.1.rolling_friction=$ROLLING")
for item in ${SET:-}; do overrides+=(--set "$item"); done
mkdir -p "$OUT/gpudem" "$OUT/liggghts"
OMP_NUM_THREADS=$NP "$BUILD"/gpudem-mpi --quiet inputs/heap/heap_fill.toml \
  --output-dir "$OUT/fill" "${overrides[@]}"
start=$SECONDS
OMP_NUM_THREADS=$NP "$BUILD"/gpudem-mpi --quiet inputs/heap/heap_lift.toml \
  --output-dir "$OUT/gpudem" --set "insert.0.bed=\"$OUT/fill/bed.h5\"" \
  --set simulation.dt=$DT "${overrides[@]}"
echo "lift: gpudem-mpi, 1 rank x $NP OpenMP threads: $((SECONDS - start)) s"
/usr/bin/python3 scripts/peers/particles.py data "$OUT/fill/bed.h5" "$OUT/liggghts/bed.data" \
  --style liggghts --density 2500 --box -0.12 0.12 -0.12 0.12 -0.01 0.45
start=$SECONDS
(cd "$OUT/liggghts" && OMP_NUM_THREADS=1 mpirun -np "$NP" liggghts \
  -in "$OLDPWD/inputs/bench/liggghts_heap.in" -var bed bed.data \
  -var stl "$OLDPWD/inputs/heap/cylinder.stl" -var dt $DT -var lift $LIFT -var rest $REST \
  -var rolling "$ROLLING" \
  -var every 2273 -log log.liggghts > /dev/null)
echo "lift: LIGGGHTS, $NP MPI ranks x 1 thread: $((SECONDS - start)) s"
last=$(ls "$OUT"/gpudem/particles_*.h5 | sort | tail -n 1)
echo "gpudem-mpi:"
/usr/bin/python3 scripts/repose_angle.py "$last"
echo "LIGGGHTS:"
/usr/bin/python3 scripts/repose_angle.py "$OUT/liggghts/heap.dump"
