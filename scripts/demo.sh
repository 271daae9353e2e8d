#!/usr/bin/env bash
# Sets up, builds and runs the tillage quickstart: about 19,000 soil spheres settle into a
# 0.8 m x 0.5 m bin and are trimmed to a 0.15 m bed (stage 1), then the cultivator sweep cuts
# through the bed at 0.08 m depth and 0.7 m/s (stage 2); the draft force is plotted to
# draft.png with its mean over the steady window, which plot_draft.py takes from the sweep's
# pass through the bed. About a minute and a half on 2 cores. NP=N runs it on N ranks (each
# with an equal share of the cores as OpenMP threads unless OMP_NUM_THREADS is set).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/mpi-env.sh
OUT=${OUT:-out/tillage-quickstart}
NP=${NP:-1}
share_cores "$NP"
BED="$OUT/bed/bed.h5"
[[ $BED = /* ]] || BED="$PWD/$BED"  # the scene resolves relative paths from its own folder
run() { mpirun -np "$NP" --bind-to none build/gpudem-mpi "$@"; }
run inputs/tillage/quickstart_bed.toml --output-dir "$OUT/bed" --quiet
run inputs/tillage/quickstart_till.toml --output-dir "$OUT/till" --set "insert.0.bed=\"$BED\""
/usr/bin/python3 scripts/plot_draft.py "$OUT/till/timeseries.csv" "$OUT/draft.png" \
  --tool sweep --scene inputs/tillage/quickstart_till.toml
cat <<MSG

Output is in $OUT:
  $OUT/draft.png              the draft, vertical and lateral force on the sweep over time,
                              each with its steady mean
  $OUT/till/particles.xmf     open it in ParaView (File > Open, pick "Xdmf3 Reader S"), then
                              apply a "Point Gaussian" representation scaled by 'radius' (or a
                              Glyph filter: Sphere, scale array 'radius', factor 2) to see the
                              spheres; open $OUT/till/sweep.xmf beside it for the tool, its
                              triangles coloured by 'pressure' (or 'force')
  $OUT/till/timeseries.csv    energies, contacts, wall forces and the sweep's force and torque
  $OUT/bed/bed.h5             the settled bed (start other tillage scenes from it)
MSG
