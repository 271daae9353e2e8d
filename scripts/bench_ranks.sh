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
exponent=${1:-6}
steps=${2:-200}
work=out/bench_ranks
mkdir -p "$work"
read -r lx ly < <(build/bench/gpudem-bench-write-bed "$exponent" "$work/bed.csv" | tail -1)
cat > "$work/scene.toml" <<TOML
[simulation]
end_time = 1.0
seed = 1

[domain]
min = [0.0, 0.0, 0.0]
max = [$lx, $ly, 0.3]
periodic = [true, true, false]

[[material]]
name = "grain"
density = 1850.0
young = 1.0e6
poisson = 0.3
restitution = 0.2
friction = 0.5

[contact]
stiffness = 2000.0

[[wall]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "grain"

[[insert]]
csv = "bed.csv"

[output]
timeseries_every = 1.0  # first and last rows only: the loop times the steps, not diagnostics
TOML
dt=$(build/gpudem-mpi "$work/scene.toml" --check | sed -n 's/^dt = \([^ ]*\) s.*/\1/p')
end_time=$(awk -v dt="$dt" -v n="$steps" 'BEGIN { printf "%.17g", dt * n }')
echo "bed of 10^$exponent spheres, $lx x $ly m, dt = $dt s, $steps steps"
for ranks in 1 2 4; do
  echo "== $ranks rank(s)"
  OMP_NUM_THREADS=1 mpirun -np "$ranks" build/gpudem-mpi "$work/scene.toml" \
    --set simulation.end_time="$end_time" --set "decomposition.dims=[$ranks,1,1]" \
    --output-dir "$work/n$ranks" | grep -E "^(decomposition|time split|done)"
done
