#!/usr/bin/env bash
# Strong and weak scaling of the host backend on 1 and 2 ranks (one OpenMP thread per rank,
# slabs along x) on the benchmarks' settled periodic bed (bench/SettledBed.hpp; Hooke, linear
# history): strong, the bed of 10^5 spheres (5 x 2 tiles) on 1 and 2 ranks; weak, 5 x 2 tiles
# on 1 rank against 10 x 2 tiles on 2 ranks. Each case runs STEPS steps from rest, ROUNDS
# times, the cases interleaved; prints each run's slowest-rank time split and halo bytes, then
# the median (range) of the loop time per case. Run it on an otherwise idle machine.
# Usage: scripts/bench_scaling.sh [STEPS (default 200)] [ROUNDS (default 3)]
# Environment: BUILD_DIR (default build).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
build=${BUILD_DIR:-build}
source scripts/mpi-env.sh
source scripts/bench_scene.sh
steps=${1:-200}
rounds=${2:-3}
work=out/bench_scaling
mkdir -p "$work"
declare -A tiles=([strong]="5 2" [weak]="10 2")
for bed in strong weak; do
  mkdir -p "$work/$bed"
  write_bench_scene "$build" "$work/$bed" "${tiles[$bed]}" > /dev/null
done
dt=$("$build"/gpudem-mpi "$work/strong/scene.toml" --check | sed -n 's/^dt = \([^ ]*\) s.*/\1/p')
end_time=$(awk -v dt="$dt" -v n="$steps" 'BEGIN { printf "%.17g", dt * n }')
cases=("strong 1" "strong 2" "weak 2")
declare -A loops
for ((round = 1; round <= rounds; ++round)); do
  for c in "${cases[@]}"; do
    read -r bed ranks <<< "$c"
    log=$(OMP_NUM_THREADS=1 mpirun --bind-to core -np "$ranks" "$build"/gpudem-mpi \
      "$work/$bed/scene.toml" --set simulation.end_time="$end_time" \
      --set "decomposition.dims=[$ranks,1,1]" --output-dir "$work/$bed/n$ranks")
    split=$(grep "^time split" <<< "$log")
    loop=$(sed -n 's/^done: [0-9]* steps in \([0-9.]*\) s.*/\1/p' <<< "$log")
    echo "round $round, $bed bed, $ranks rank(s): $split; loop $loop s"
    loops[$c]+="$loop "
  done
done
echo "| case | particles per rank | ranks | loop of $steps steps [s], median (range) |"
echo "|---|---|---|---|"
for c in "${cases[@]}"; do
  read -r bed ranks <<< "$c"
  echo "${loops[$c]}" | tr ' ' '\n' | grep . | sort -g | awk -v c="$bed" -v r="$ranks" '
    { v[NR] = $1 } END {
      m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
      printf "| %s | %d | %d | %.3g (%.3g-%.3g) |\n", c, (c == "strong" ? 100000 / r : 100000), r, m, v[1], v[NR] }'
done
