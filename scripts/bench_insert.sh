#!/usr/bin/env bash
# Box insertion at start-up (bench/InsertionBenchmark.cpp): 10^EXPONENT spheres of radius
# 1 ± 0.5 mm at a solid fraction of 0.3 in a box ASPECT times as long as it is wide, placed
# sequentially and by tiles on 1 rank with 1 and 2 OpenMP threads, and by tiles on 2 and 4
# ranks of one thread each; seconds, spheres/s and the peak memory of a rank. Run it on an
# idle machine.
# Usage: scripts/bench_insert.sh [EXPONENT (default 6)] [ASPECT (default 1)]
# Environment: BUILD_DIR (default build), as for scripts/setup.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
bench=${BUILD_DIR:-build}/bench/gpudem-bench-insert
args=(--count "1e${1:-6}" --aspect "${2:-1}")
echo "10^${1:-6} spheres, box ${2:-1} : 1 : 1"
OMP_NUM_THREADS=1 mpirun -np 1 --bind-to none "$bench" "${args[@]}" --placement sequential --header
OMP_NUM_THREADS=2 mpirun -np 1 --bind-to none "$bench" "${args[@]}" --placement sequential
for threads in 1 2; do
  OMP_NUM_THREADS=$threads mpirun -np 1 --bind-to none "$bench" "${args[@]}" --placement tiled
done
for ranks in 2 4; do
  OMP_NUM_THREADS=1 mpirun -np "$ranks" --bind-to none "$bench" "${args[@]}" --placement sequential
  OMP_NUM_THREADS=1 mpirun -np "$ranks" --bind-to none "$bench" "${args[@]}" --placement tiled
done
