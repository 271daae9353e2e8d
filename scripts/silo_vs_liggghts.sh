#!/usr/bin/env bash
# Side by side on one machine: the silo discharge of inputs/silo/silo_discharge.toml in
# gpudem-mpi (host backend, one rank, NP OpenMP threads) and in LIGGGHTS (Debian's liggghts, NP
# MPI ranks) from the same settled bed, through the same STL plates, with the same materials,
# Hertz-Mindlin stiffnesses and dashpots, time step and skin (inputs/bench/liggghts_silo.in;
# the Coulomb limits differ in detail), for each orifice diameter.
# Prints each run's wall time, then each code's discharge rates and, with four diameters or
# more, its Beverloo fit (scripts/beverloo_fit.py). Installs Debian's liggghts when missing.
# The bed is BED (default: the one scripts/silo_beverloo.sh leaves in out/silo/fill/bed.h5;
# made by inputs/silo/silo_fill.toml when missing).
# Usage: scripts/silo_vs_liggghts.sh [OUT (default out/silo-liggghts)]
#   DIAMETERS  orifice diameters in m (default "0.024 0.028 0.032 0.036 0.040")
#   NP         cores for each code (default 2); BUILD_DIR as for setup.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh liggghts > /dev/null
source scripts/mpi-env.sh
OUT=${1:-out/silo-liggghts}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
NP=${NP:-2}
DIAMETERS=${DIAMETERS:-"0.024 0.028 0.032 0.036 0.040"}
BUILD=${BUILD_DIR:-build}
BED=${BED:-$PWD/out/silo/fill/bed.h5}
DT=2.2e-5
STEPS=18182  # 0.4 s
mkdir -p "$OUT"
if [[ ! -f $BED ]]; then
  OMP_NUM_THREADS=$NP "$BUILD"/gpudem-mpi --quiet inputs/silo/silo_fill.toml \
    --output-dir "$(dirname "$BED")"
fi
/usr/bin/python3 scripts/peers/particles.py data "$BED" "$OUT/bed.data" \
  --style liggghts --density 2500 --box -0.001 0.121 -0.001 0.121 -0.02 0.25
ours=() theirs=()
for D in $DIAMETERS; do
  dir="$OUT/orifice-$D"
  mkdir -p "$dir/gpudem" "$dir/liggghts"
  /usr/bin/python3 scripts/make_orifice_stl.py "$dir/orifice.stl" --side 0.12 --diameter "$D"
  start=$SECONDS
  OMP_NUM_THREADS=$NP "$BUILD"/gpudem-mpi --quiet inputs/silo/silo_discharge.toml \
    --output-dir "$dir/gpudem" --set "insert.0.bed=\"$BED\"" \
    --set "mesh.0.file=\"$dir/orifice.stl\"" --set simulation.dt=$DT --set output.every=0
  echo "D = $D m: gpudem-mpi, 1 rank x $NP OpenMP threads: $((SECONDS - start)) s"
  start=$SECONDS
  (cd "$dir/liggghts" && OMP_NUM_THREADS=1 mpirun -np "$NP" liggghts \
    -in "$OLDPWD/inputs/bench/liggghts_silo.in" -var bed "$OUT/bed.data" \
    -var stl ../orifice.stl -var dt $DT -var steps $STEPS -var every 227 -log log.liggghts \
    > /dev/null)
  echo "D = $D m: LIGGGHTS, $NP MPI ranks x 1 thread: $((SECONDS - start)) s"
  # its thermo rows (step time atoms ke cpu) as the time and removed columns of a time series
  awk 'BEGIN { print "time,removed" }
       $1 == "Step" { on = 1; next }
       on && $1 ~ /^[0-9]+$/ && NF == 5 { if (n0 == "") n0 = $3; print $2 "," n0 - $3; next }
       on { on = 0 }' "$dir/liggghts/log.liggghts" > "$dir/liggghts/timeseries.csv"
  ours+=("$D=$dir/gpudem")
  theirs+=("$D=$dir/liggghts")
done
for code in gpudem-mpi LIGGGHTS; do
  echo "$code:"
  runs=("${ours[@]}")
  [[ $code = LIGGGHTS ]] && runs=("${theirs[@]}")
  /usr/bin/python3 scripts/beverloo_fit.py "$BED" "${runs[@]}" || true
done
