#!/usr/bin/env bash
# Cost of parallel bonds: the benchmarks' settled periodic bed of 10^EXPONENT spheres
# (bench/SettledBed.hpp; Hooke, linear history, scripts/bench_scene.sh) run for STEPS steps as it
# lies, and the same bed with every two grains whose surfaces are within GAP of each other joined
# by a bond as stiff as the grains (E = 1 MPa, no strength: none breaks), both at the same
# explicit dt (the bonded bed's automatic step). REPS runs of each, interleaved, one rank, NP
# threads. Prints per run the bonds, the force part of the time split and the whole loop [s], and
# the bond records' bytes (--verbose memory report) per bond.
# Usage: scripts/bond_cost.sh [OUT (default out/bond-cost)]
#   EXPONENT (4), STEPS (2000), REPS (3), GAP [m] (1e-4), NP (1); BUILD_DIR as for setup.sh
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/bench_scene.sh
OUT=${1:-out/bond-cost}
[[ $OUT = /* ]] || OUT="$PWD/$OUT"
BUILD=${BUILD_DIR:-build}
EXPONENT=${EXPONENT:-4}
STEPS=${STEPS:-2000}
REPS=${REPS:-3}
GAP=${GAP:-1e-4}
NP=${NP:-1}
mkdir -p "$OUT"
[[ -f "$OUT/scene.toml" ]] || write_bench_scene "$BUILD" "$OUT" "$EXPONENT"
cat > "$OUT/bonds.toml" <<TOML
[[bond]]
materials = ["grain", "grain"]
gap = $GAP
young = 1.0e6
poisson = 0.3
damping_ratio = 0.1
TOML
cat "$OUT/scene.toml" "$OUT/bonds.toml" > "$OUT/bonded.toml"
dt=$("$BUILD"/gpudem-mpi --check "$OUT/bonded.toml" | sed -n 's/^dt = \([0-9.e+-]*\) s.*/\1/p')
end=$(/usr/bin/python3 -c "print($STEPS * $dt)")
run() {  # run NAME SCENE: one timed run, its output in OUT/NAME
  local log="$OUT/$1.log"
  OMP_NUM_THREADS=$NP "$BUILD"/gpudem-mpi --verbose "$2" --output-dir "$OUT/$1" \
    --set "simulation.dt=$dt" --set "simulation.end_time=$end" > "$log"
  local forces total bonds particles bytes
  forces=$(sed -n 's/.*time split (slowest rank): integration [^,]*, forces \([0-9.e+-]*\) s.*/\1/p' "$log")
  total=$(sed -n 's/^done: [0-9]* steps in \([0-9.]*\) s.*/\1/p' "$log")
  bonds=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "bonds") c = i } NR == 2 { print (c ? $c : 0) }' "$OUT/$1/timeseries.csv")
  particles=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "particles") c = i } NR == 2 { print $c }' "$OUT/$1/timeseries.csv")
  bytes=$(awk -v n="$bonds" -v p="$particles" '$1 == "bonds" && n > 0 { print $2 * p / n }' "$log")
  echo "$1: bonds $bonds  forces $forces s  loop $total s  bond bytes per bond ${bytes:--}"
}
echo "dt $dt s, $STEPS steps, 10^$EXPONENT spheres, $NP thread(s)"
for rep in $(seq "$REPS"); do
  run "plain_$rep" "$OUT/scene.toml"
  run "bonded_$rep" "$OUT/bonded.toml"
done
