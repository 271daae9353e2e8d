#!/usr/bin/env bash
# The side-by-side of gpudem-mpi, LIGGGHTS and LAMMPS on one machine, from one set of particles:
# the bed of inputs/bench/peers_bed.toml (20,000 soil spheres poured into a 1.0 m x 0.7 m bin,
# Hertz-Mindlin with history, dt = 1e-4 s, skin 4 mm). gpudem-mpi inserts the particles once;
# each code then settles them for SETTLE steps and runs its own settled bed SETTLED steps more,
# on RANKS MPI ranks of one thread each (the peers' input files: inputs/bench/liggghts_peers.in,
# inputs/bench/lammps_peers.in). Installs Debian's liggghts and lammps when missing. Prints one
# table: the stepping time of each phase (the peers' "Loop time", our "done" line),
# particle-steps/s per core, the peak memory of all ranks, and the observables at the end of
# each phase (bed height, packing fraction of the lower half of the bed, kinetic energy) with
# their differences from ours. Run it on an otherwise idle machine: codes run one at a time.
# Installs Debian's time (/usr/bin/time) for the memory figures.
# Usage: scripts/peers/compare.sh [SETTLE (default 15000)] [SETTLED (default 2000)]
# Environment: RANKS (default 2), BUILD_DIR (default build), OUT (default out/peers/compare).
set -euo pipefail
cd "$(dirname "$0")/../.."
settle=${1:-15000}
settled=${2:-2000}
ranks=${RANKS:-2}
out=${OUT:-out/peers/compare}
if ((settle % 500 || settle < 500 || settled < 1)); then
  echo "usage: $0 [SETTLE (a multiple of 500)] [SETTLED (> 0)]" >&2
  exit 2
fi
scripts/setup.sh liggghts lammps time > /dev/null
gpudem=$(cd "${BUILD_DIR:-build}" && pwd)/gpudem-mpi
source scripts/mpi-env.sh
export OMP_NUM_THREADS=1
particles=scripts/peers/particles.py
density=1850.0
area=0.7  # m^2, the bin's floor
rm -rf "$out"
mkdir -p "$out"/{pour,gpudem,liggghts,lammps}
out=$(cd "$out" && pwd)

# Our scenes, from the shipped one: pour (insertion, one step), then settle from the CSV.
scene=inputs/bench/peers_bed.toml
sed -n '/^\[preparation\]/q;p' "$scene" > "$out/pour/scene.toml"
sed -e '/^region = /d' -e '/^count = /d' -e '/^radius = /d' \
  -e 's|^\[\[insert\]\]|[[insert]]\ncsv = "../particles.csv"|' \
  -e "s|^dir = .*|dir = \"$out/gpudem/settle\"|" "$scene" > "$out/gpudem/settle.toml"
"$gpudem" "$out/pour/scene.toml" --quiet --output-dir "$out/pour" \
  --set simulation.end_time=1e-4 > /dev/null
/usr/bin/python3 "$particles" csv "$out/pour/particles_000000.h5" "$out/particles.csv"
for code in liggghts lammps; do
  /usr/bin/python3 "$particles" data "$out/particles.csv" "$out/$code/bed.data" --style "$code" \
    --density "$density" --box 0 1 0 0.7 0 0.4
done

# Runs a command on RANKS ranks in folder $1, each rank's peak resident set [kB] written to
# $1/peak.<rank> by /usr/bin/time; peak_mb sums them.
ranks_run() {
  local dir=$1
  shift
  rm -f "$dir"/peak.*
  local binding=core
  (($ranks > $(getconf _NPROCESSORS_ONLN))) && binding=none
  (cd "$dir" && mpirun --bind-to "$binding" -np "$ranks" bash -c \
    'exec /usr/bin/time -o "peak.$OMPI_COMM_WORLD_RANK" -f %M "$@"' _ "$@")
}
peak_mb() {
  cat "$1"/peak.* | awk '{ s += $1 } END { printf "%.0f", s / 1024 }'
}
stepping_seconds() {  # the stepping time of gpudem-mpi's "done" line in log $1
  sed -n 's/^done: [0-9]* steps in \([0-9.]*\) s.*/\1/p' "$1"
}
observe() {
  /usr/bin/python3 "$particles" observe "$1" --density "$density" --area "$area"
}
declare -A seconds memory state

# gpudem-mpi: the settle run writes its bed at the last step; the settled run continues it.
t_settle=$(awk -v n="$settle" 'BEGIN { printf "%.10g", n * 1e-4 }')
t_end=$(awk -v n="$settle" 'BEGIN { printf "%.10g", (n + 1) * 1e-4 }')  # the bed: at t_settle
failed() {
  echo "$1 failed: see $2" >&2
  exit 1
}
ranks_run "$out/gpudem" "$gpudem" settle.toml --set simulation.end_time="$t_end" \
  --set preparation.check_after="$t_settle" --set preparation.bed_file="\"$out/gpudem/bed.h5\"" \
  > "$out/gpudem/settle.log" 2>&1 || failed "gpudem-mpi's settling" "$out/gpudem/settle.log"
seconds[gpudem.settle]=$(stepping_seconds "$out/gpudem/settle.log")
memory[gpudem.settle]=$(peak_mb "$out/gpudem")
state[gpudem.settle]=$(observe "$out/gpudem/bed.h5")
t_settled=$(awk -v n="$settled" 'BEGIN { printf "%.10g", n * 1e-4 }')
sed -e '/^\[\[insert\]\]/,$d' "$out/gpudem/settle.toml" > "$out/gpudem/settled.toml"
cat >> "$out/gpudem/settled.toml" <<TOML
[[insert]]
bed = "bed.h5"

[output]
dir = "$out/gpudem/settled"
every = $t_settled
timeseries_every = $t_settled
TOML
ranks_run "$out/gpudem" "$gpudem" settled.toml --set simulation.end_time="$t_settled" \
  > "$out/gpudem/settled.log" 2>&1 || failed "gpudem-mpi's settled run" "$out/gpudem/settled.log"
seconds[gpudem.settled]=$(stepping_seconds "$out/gpudem/settled.log")
memory[gpudem.settled]=$(peak_mb "$out/gpudem")
state[gpudem.settled]=$(observe "$(ls "$out"/gpudem/settled/particles_*.h5 | tail -n 1)")

run_peer() {  # code binary input
  local code=$1 binary=$2 input=$3
  ranks_run "$out/$code" "$binary" -in "$PWD/$input" -var bed bed.data -var settle "$settle" \
    -var settled "$settled" -log log.lammps > "$out/$code/run.log" 2>&1 ||
    failed "$code" "$out/$code/run.log"
  mapfile -t loops < <(sed -n 's/^Loop time of \([0-9.e+-]*\) on.*/\1/p' "$out/$code/log.lammps")
  seconds[$code.settle]=${loops[0]}
  seconds[$code.settled]=${loops[1]}
  memory[$code.settle]=$(peak_mb "$out/$code")
  memory[$code.settled]=${memory[$code.settle]}
  state[$code.settle]=$(observe "$out/$code/settle.dump")
  state[$code.settled]=$(observe "$out/$code/settled.dump")
}
run_peer liggghts liggghts inputs/bench/liggghts_peers.in
run_peer lammps lmp inputs/bench/lammps_peers.in

echo "| code | phase | steps | stepping [s] | particle-steps/s per core | peak memory, all ranks [MB] | particles | bed height [m] | packing fraction | kinetic energy [J] | height, packing vs ours |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for phase in settle settled; do
  steps=$([[ $phase == settle ]] && echo "$settle" || echo "$settled")
  IFS=, read -r _ h0 p0 _ <<< "${state[gpudem.$phase]}"
  for code in gpudem liggghts lammps; do
    IFS=, read -r n h p ke <<< "${state[$code.$phase]}"
    awk -v c="$code" -v ph="$phase" -v st="$steps" -v s="${seconds[$code.$phase]}" \
      -v r="$ranks" -v m="${memory[$code.$phase]}" -v n="$n" -v h="$h" -v p="$p" -v ke="$ke" \
      -v h0="$h0" -v p0="$p0" 'BEGIN {
        printf "| %s | %s | %d | %.3g | %.3g | %s | %d | %.4f | %.4f | %.3g | %+.1f %%, %+.1f %% |\n",
          c, ph, st, s, n * st / s / r, m, n, h, p, ke, 100 * (h / h0 - 1), 100 * (p / p0 - 1) }'
  done
done
