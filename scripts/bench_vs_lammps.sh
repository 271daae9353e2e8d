#!/usr/bin/env bash
# Side-by-side on one machine: gpudem-mpi's host backend and LAMMPS (Debian's lmp, GRANULAR
# package, gran/hooke/history) on the same settled bed of 10^5 spheres, one core each.
# Installs Debian's lammps when missing.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh lammps > /dev/null
source scripts/mpi-env.sh
work=$(mktemp -d)
echo "gpudem-mpi (host backend):"
build/bench/gpudem-bench-host 5 "$work/bed.data" | grep -E "^\| (particles|100000)"
version=$(lmp -h | sed -n 's/^Large-scale Atomic\/Molecular Massively Parallel Simulator - //p')
echo "LAMMPS $version (gran/hooke/history), 1 and 2 MPI ranks:"
for ranks in 1 2; do
  (cd "$work" && OMP_NUM_THREADS=1 mpirun -np "$ranks" lmp -in "$OLDPWD/inputs/bench/lammps_bed.in" \
     -var bed bed.data -log log.$ranks > /dev/null)
  loop=$(grep "^Loop time" "$work/log.$ranks" | tail -1)
  seconds=$(echo "$loop" | awk '{print $4}')
  echo "| 100000 | $ranks rank(s) | 300 | $(awk -v s="$seconds" 'BEGIN{printf "%.3g", 300*100000/s}') particle-steps/s | ($loop)"
  grep -E "^(Ave neighs/atom|Neighbor list builds)" "$work/log.$ranks" | tail -2 | sed 's/^/    /'
done
rm -rf "$work"
