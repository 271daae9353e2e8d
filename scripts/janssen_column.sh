#!/usr/bin/env bash
# Janssen's effect in a square column, in gpudem-mpi and, side by side on the same machine, in
# LIGGGHTS (Debian's liggghts): for each grain count, inputs/silo/janssen_fill.toml pours and
# settles a column (gpudem-mpi), then both codes slide its four side walls up at 10 mm/s for
# 0.4 s from that same settled column (inputs/silo/janssen_slide.toml and
# inputs/bench/liggghts_janssen.in: same walls, materials, Hertz-Mindlin, time step and skin).
# scripts/janssen_fit.py then fits M_app = M_sat (1 - exp(-M / M_sat)) to each code's floor
# loads. Installs Debian's liggghts when missing.
# Usage: scripts/janssen_column.sh [OUT (default out/janssen)]
#   COUNTS    grain counts (default "500 1000 1800 2800 4400": fills of about 0.5 to 4 L)
#   NP        cores for each code (default 2); BUILD_DIR as for setup.sh
#   LIGGGHTS  0: gpudem-mpi only
set -euo pipefail
cd "$(dirname "$0")/.."
PEER=${LIGGGHTS:-1}
peers=()
[[ $PEER != 0 ]] && peers=(liggghts)
scripts/setup.sh "${peers[@]}" > /dev/null
source scripts/mpi-env.sh
OUT=${1:-out/janssen}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
NP=${NP:-2}
COUNTS=${COUNTS:-"500 1000 1800 2800 4400"}
BUILD=${BUILD_DIR:-build}
DT=4.4e-5     # both codes' slide step (gpudem-mpi's "auto" at dt_fraction 0.2)
STEPS=9091    # 0.4 s
EVERY=23      # LIGGGHTS thermo rows about every 0.001 s, as the time series
ours=() theirs=()
for N in $COUNTS; do
  dir="$OUT/count-$N"
  mkdir -p "$dir/gpudem" "$dir/liggghts"
  # pour box: the grains at a solid fraction of 0.33 of the volume their centres can take
  height=$(awk -v n="$N" 'BEGIN { v = 4 / 3 * 3.141592653589793 * 2e-3 ^ 3; i = 0.04 - 4.4e-3
                                  printf "%.4f", 1.01 * n * v / (0.33 * i * i) + 4.4e-3 }')
  OMP_NUM_THREADS=$NP "$BUILD"/gpudem-mpi --quiet inputs/silo/janssen_fill.toml \
    --output-dir "$dir/fill" --set "insert.0.count=$N" \
    --set "insert.0.region.max=[0.04, 0.04, $height]"
  start=$SECONDS
  OMP_NUM_THREADS=$NP "$BUILD"/gpudem-mpi --quiet inputs/silo/janssen_slide.toml \
    --output-dir "$dir/gpudem" --set "insert.0.bed=\"$dir/fill/bed.h5\"" \
    --set simulation.dt=$DT
  echo "$N grains: gpudem-mpi, 1 rank x $NP OpenMP threads: $((SECONDS - start)) s"
  ours+=("$dir/fill/bed.h5=$dir/gpudem")
  [[ $PEER = 0 ]] && continue
  /usr/bin/python3 scripts/peers/particles.py data "$dir/fill/bed.h5" "$dir/liggghts/bed.data" \
    --style liggghts --density 2500 --box -0.003 0.043 -0.003 0.043 -0.012 0.32
  start=$SECONDS
  (cd "$dir/liggghts" && OMP_NUM_THREADS=1 mpirun -np "$NP" liggghts \
    -in "$OLDPWD/inputs/bench/liggghts_janssen.in" -var bed bed.data \
    -var wall "$OLDPWD/inputs/silo/column_wall.stl" \
    -var floor "$OLDPWD/inputs/bench/liggghts_column_floor.stl" \
    -var dt $DT -var steps $STEPS -var every $EVERY -log log.liggghts > /dev/null)
  echo "$N grains: LIGGGHTS, $NP MPI ranks x 1 thread: $((SECONDS - start)) s"
  # its thermo rows (step time atoms ke, then the mesh forces) under the time series' names
  awk 'BEGIN { print "time,floor_fz,x0_fx,x0_fz,x1_fx,x1_fz,y0_fy,y0_fz,y1_fy,y1_fz" }
       $1 == "Step" { on = 1; next }
       on && $1 ~ /^[0-9]+$/ && NF == 13 {
         printf "%s", $2; for (k = 5; k <= 13; ++k) printf ",%s", $k; print ""; next }
       on { on = 0 }' "$dir/liggghts/log.liggghts" > "$dir/liggghts/timeseries.csv"
  theirs+=("$dir/fill/bed.h5=$dir/liggghts")
done
echo "gpudem-mpi:"
/usr/bin/python3 scripts/janssen_fit.py "${ours[@]}"
if [[ $PEER != 0 ]]; then
  echo "LIGGGHTS:"
  /usr/bin/python3 scripts/janssen_fit.py "${theirs[@]}"
fi
