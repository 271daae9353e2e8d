#!/usr/bin/env bash
# Cost of snapshot output with and without the writer thread (output.asynchronous) on the
# benchmarks' settled periodic bed of 10^EXPONENT spheres (bench/SettledBed.hpp; Hooke, linear
# history; host backend), STEPS steps from rest with a snapshot every EVERY steps, on RANKS
# ranks of one OpenMP thread each (slabs along x): wall time of the run, the time the loop
# spent on output, the time the writer thread spent writing and the size of one snapshot file.
# Further arguments are scene settings for both runs (--set), e.g. 'output.precision="float"'
# 'output.fields=["velocity","id"]'. Run it on an idle machine.
# Usage: scripts/bench_output.sh [EXPONENT (4..6, default 5)] [STEPS (default 200)]
#                                [EVERY (default 10)] [RANKS (default 1)] [KEY=VALUE...]
# Environment: BUILD_DIR (default build), as for scripts/setup.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
source scripts/mpi-env.sh
source scripts/bench_scene.sh
build=${BUILD_DIR:-build}
exponent=${1:-5}
steps=${2:-200}
every=${3:-10}
ranks=${4:-1}
settings=()
for setting in "${@:5}"; do settings+=(--set "$setting"); done
work=out/bench_output
mkdir -p "$work"
write_bench_scene "$build" "$work" "$exponent"
dt=$("$build"/gpudem-mpi "$work/scene.toml" --check | sed -n 's/^dt = \([^ ]*\) s.*/\1/p')
end_time=$(awk -v dt="$dt" -v n="$steps" 'BEGIN { printf "%.17g", dt * n }')
output_every=$(awk -v dt="$dt" -v n="$every" 'BEGIN { printf "%.17g", dt * n }')
echo "bed of 10^$exponent spheres, $steps steps, a snapshot every $every steps, $ranks rank(s)" \
  "${*:5}"
for asynchronous in false true; do
  echo "== output.asynchronous = $asynchronous"
  OMP_NUM_THREADS=1 mpirun -np "$ranks" "$build"/gpudem-mpi "$work/scene.toml" \
    --set simulation.end_time="$end_time" --set output.every="$output_every" \
    --set output.asynchronous=$asynchronous --set "decomposition.dims=[$ranks,1,1]" \
    "${settings[@]}" --output-dir "$work/async_$asynchronous" |
    grep -E "^(snapshots|time split|done)"
  echo "snapshot file: $(stat -c %s "$work/async_$asynchronous/particles_000000.h5") bytes"
done
