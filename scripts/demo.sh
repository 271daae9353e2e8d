#!/usr/bin/env bash
# Sets up, builds and runs the quickstart scene: a soil bin filled and settled under gravity.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/mpi-env.sh
OUT=${OUT:-out/quickstart}
NP=${NP:-1}
mpirun -np "$NP" --bind-to none build/gpudem-mpi inputs/quickstart.toml --output-dir "$OUT"
cat <<MSG

Output is in $OUT:
  $OUT/particles.xmf     open it in ParaView (File > Open, pick the "Xdmf3 Reader"), then
                         apply a "Point Gaussian" representation scaled by 'radius' (or a Glyph
                         filter: Sphere, scale array 'radius', factor 2) to see the spheres
  $OUT/particles_*.h5    the snapshots (HDF5; h5ls -r to list)
  $OUT/timeseries.csv    energies, contact count, wall forces over time
MSG
