#!/usr/bin/env bash
# Time split of the steps on 1, 2 and 4 ranks (host backend, one OpenMP thread per rank) on the
# benchmarks' settled periodic bed of 10^EXPONENT spheres (bench/SettledBed.hpp; Hooke, linear
# history), STEPS steps from rest, slabs along x: forces, neighbour lists, ghost exchange,
# migration and output per rank, and the halo bytes a rank sends per step.
# Usage: scripts/bench_ranks.sh [EXPONENT (4..6, default 6)] [STEPS (default 200)]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
source scripts/bench_scene.sh
exponent=${1:-6}
steps=${2:-200}
work=out/bench_ranks
mkdir -p "$work"
write_bench_scene build "$work" "$exponent"
dt=$(build/gpudem-mpi "$work/scene.toml" --check | sed -n 's/^dt = \([^ ]*\) s.*/\1/p')
end_time=$(awk -v dt="$dt" -v n="$steps" 'BEGIN { printf "%.17g", dt * n }')
echo "bed of 10^$exponent spheres, $lx x $ly m, dt = $dt s, $steps steps"
for ranks in 1 2 4; do
  echo "== $ranks rank(s)"
  OMP_NUM_THREADS=1 mpirun -np "$ranks" build/gpudem-mpi "$work/scene.toml" \
    --set simulation.end_time="$end_time" --set "decomposition.dims=[$ranks,1,1]" \
    --output-dir "$work/n$ranks" | grep -E "^(decomposition|time split|done)"
done
