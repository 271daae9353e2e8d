#!/usr/bin/env bash
# The side-by-side of gpudem-mpi, LIGGGHTS, LAMMPS and ESyS-Particle on one machine, from one
# set of particles: the bed of inputs/bench/peers_bed.toml (20,000 soil spheres poured into a
# 1.0 m x 0.7 m bin, Hertz-Mindlin with history, dt = 1e-4 s, skin 4 mm). gpudem-mpi inserts
# the particles once; each code then settles them for SETTLE steps and runs its own settled
# bed SETTLED steps more, on RANKS MPI ranks of one thread each (the peers' inputs:
# inputs/bench/liggghts_peers.in, lammps_peers.in, esys_peers.py; ESyS-Particle runs RANKS
# workers under one master rank, which waits, and its particle-steps/s per core count the
# workers). Then each code but ESyS-Particle, whose triangle walls are frictionless linear
# springs, drags a plate through gpudem-mpi's settled bed for PLATE steps: a vertical
# rectangle 0.2 m wide, from 0.04 m above the floor to above the bed's top (0.14 m), starting at
# x = 0.25 m and moving along +x at 1 m/s, the particles that touch its start or the 2 mm
# behind it left out (inputs/bench/liggghts_plate.in, lammps_plate.in; LAMMPS' plate is a 2 mm
# block). Installs Debian's liggghts, lammps and esys-particle (with ESYS=1) when missing.
# Prints two tables: the stepping time of each phase (the peers' "Loop time", our "done" line),
# particle-steps/s per core, the peak memory of all ranks, and the observables at the end of
# each phase (bed height, packing fraction of the lower half of the bed, kinetic energy), or
# the plate's draft (the particles' force on it against its travel) over the second half of
# the drag, mean and standard deviation, each with its difference from ours. Run it on an
# otherwise idle machine: codes run one at a time. Installs Debian's time (/usr/bin/time) for
# the memory figures.
# Usage: scripts/peers/compare.sh [SETTLE (default 15000)] [SETTLED (default 2000)]
#        [PLATE (default 3000, even)]
# Environment: RANKS (default 2), BUILD_DIR (default build), OUT (default out/peers/compare),
#   ESYS (default 1; 0 leaves ESyS-Particle out, whose settling takes eight times ours).
set -euo pipefail
cd "$(dirname "$0")/../.."
unset PROCS  # set only for ESyS-Particle's run (ranks_run)
settle=${1:-15000}
settled=${2:-2000}
drag=${3:-3000}
ranks=${RANKS:-2}
esys=${ESYS:-1}
out=${OUT:-out/peers/compare}
if ((settle % 500 || settle < 500 || settled < 1 || drag < 20 || drag % 2)) ||
  [[ $esys != [01] ]]; then
  echo "usage: [ESYS=0|1] $0 [SETTLE (a multiple of 500)] [SETTLED (> 0)] [PLATE (even, >= 20)]" >&2
  exit 2
fi
peers=(liggghts lammps time)
[[ $esys == 1 ]] && peers+=(esys-particle)
scripts/setup.sh "${peers[@]}" > /dev/null
gpudem=$(cd "${BUILD_DIR:-build}" && pwd)/gpudem-mpi
source scripts/mpi-env.sh
export OMP_NUM_THREADS=1
particles=scripts/peers/particles.py
density=1850.0
area=0.7  # m^2, the bin's floor
rm -rf "$out"
mkdir -p "$out"/pour "$out"/esys "$out"/{gpudem,liggghts,lammps}/plate
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

# Runs a command on RANKS ranks (PROCS, when set) in folder $1, each rank's peak resident set
# [kB] written to $1/peak.<rank> by /usr/bin/time; peak_mb sums them.
ranks_run() {
  local dir=$1 procs=${PROCS:-$ranks}
  shift
  rm -f "$dir"/peak.*
  local binding=core
  ((procs > $(getconf _NPROCESSORS_ONLN))) && binding=none
  (cd "$dir" && mpirun --bind-to "$binding" -np "$procs" bash -c \
    'exec /usr/bin/time -o "peak.$OMPI_COMM_WORLD_RANK" -f %M "$@"' _ "$@")
}
peak_mb() {
  cat "$1"/peak.* | awk '{ s += $1 } END { printf "%.0f", s / 1024 }'
}
loop_seconds() {  # the peers' "Loop time of SECONDS on" lines in log $1, one per phase
  sed -n 's/^Loop time of \([0-9.e+-]*\) on.*/\1/p' "$1"
}
stepping_seconds() {  # the stepping time of gpudem-mpi's "done" line in log $1
  sed -n 's/^done: [0-9]* steps in \([0-9.]*\) s.*/\1/p' "$1"
}
observe() {
  /usr/bin/python3 "$particles" observe "$1" --density "$density" --area "$area"
}
declare -A seconds memory state force counts

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
  mapfile -t loops < <(loop_seconds "$out/$code/log.lammps")
  seconds[$code.settle]=${loops[0]}
  seconds[$code.settled]=${loops[1]}
  memory[$code.settle]=$(peak_mb "$out/$code")
  memory[$code.settled]=${memory[$code.settle]}
  state[$code.settle]=$(observe "$out/$code/settle.dump")
  state[$code.settled]=$(observe "$out/$code/settled.dump")
}
run_peer liggghts liggghts inputs/bench/liggghts_peers.in
run_peer lammps lmp inputs/bench/lammps_peers.in
settling_codes="gpudem liggghts lammps"
if [[ $esys == 1 ]]; then
  settling_codes+=" esys"
  PROCS=$((ranks + 1)) ranks_run "$out/esys" esysparticle "$PWD/inputs/bench/esys_peers.py" \
    "$out/particles.csv" "$settle" "$settled" "$ranks" > "$out/esys/run.log" 2>&1 ||
    failed esys-particle "$out/esys/run.log"
  mapfile -t loops < <(loop_seconds "$out/esys/run.log")
  seconds[esys.settle]=${loops[0]}
  seconds[esys.settled]=${loops[1]}
  memory[esys.settle]=$(peak_mb "$out/esys")
  memory[esys.settled]=${memory[esys.settle]}
  state[esys.settle]=$(observe "$out/esys/settle.dump")
  state[esys.settled]=$(observe "$out/esys/settled.dump")
fi

# The plate drag, from gpudem-mpi's settled bed, in gpudem-mpi, LIGGGHTS and LAMMPS.
plate=(0.25 0.25 0.45 0.04 0.30)  # X Y0 Y1 Z0 Z1 [m]: the plate's plane x = X at the start
speed=1.0                         # m/s along +x
every=10                          # steps between force samples
t_drag=$(awk -v n="$drag" 'BEGIN { printf "%.10g", n * 1e-4 }')
t_half=$(awk -v n="$drag" 'BEGIN { printf "%.10g", n / 2 * 1e-4 }')
/usr/bin/python3 "$particles" slot "$out/gpudem/bed.h5" "$out/gpudem/plate/particles.csv" \
  --plate "${plate[@]}" --thickness 0.002 2> "$out/gpudem/plate/slot.log"
/usr/bin/python3 "$particles" plate "$out/gpudem/plate/plate.stl" --plate "${plate[@]}"
for code in liggghts lammps; do
  /usr/bin/python3 "$particles" data "$out/gpudem/plate/particles.csv" "$out/$code/plate/bed.data" \
    --style "$code" --density "$density" --box 0 1 0 0.7 0 0.4
done
sed -e '/^\[\[insert\]\]/,$d' "$out/gpudem/settle.toml" > "$out/gpudem/plate/scene.toml"
cat >> "$out/gpudem/plate/scene.toml" <<TOML
[[mesh]]
name = "plate"
file = "plate.stl"
material = "soil"

[mesh.motion]
times = [0.0, $t_drag]
velocities = [[$speed, 0.0, 0.0], [$speed, 0.0, 0.0]]

[[insert]]
csv = "particles.csv"

[output]
dir = "$out/gpudem/plate/run"
every = $t_drag
timeseries_every = $(awk -v n="$every" 'BEGIN { printf "%.10g", n * 1e-4 }')
TOML
ranks_run "$out/gpudem/plate" "$gpudem" scene.toml --set simulation.end_time="$t_drag" \
  > "$out/gpudem/plate/run.log" 2>&1 || failed "gpudem-mpi's plate drag" "$out/gpudem/plate/run.log"
seconds[gpudem.plate]=$(stepping_seconds "$out/gpudem/plate/run.log")
memory[gpudem.plate]=$(peak_mb "$out/gpudem/plate")
force[gpudem]=$(/usr/bin/python3 "$particles" force "$out/gpudem/plate/run/timeseries.csv" \
  --column plate_fx --from "$t_half")
counts[gpudem]=$(observe "$(ls "$out"/gpudem/plate/run/particles_*.h5 | tail -n 1)" | cut -d, -f1)
run_plate() {  # code binary input, then the input's variables
  local code=$1 binary=$2 input=$3
  shift 3
  ranks_run "$out/$code/plate" "$binary" -in "$PWD/$input" -var bed bed.data -var speed "$speed" \
    -var steps "$drag" -var every "$every" "$@" -log log.lammps > "$out/$code/plate/run.log" 2>&1 ||
    failed "$code's plate drag" "$out/$code/plate/run.log"
  seconds[$code.plate]=$(loop_seconds "$out/$code/plate/log.lammps")
  memory[$code.plate]=$(peak_mb "$out/$code/plate")
  force[$code]=$(/usr/bin/python3 "$particles" force "$out/$code/plate/plate_force.txt" \
    --column plate_fx --from "$t_half")
  counts[$code]=$(observe "$out/$code/plate/plate.dump" | cut -d, -f1)
}
run_plate liggghts liggghts inputs/bench/liggghts_plate.in -var plate "$out/gpudem/plate/plate.stl"
run_plate lammps lmp inputs/bench/lammps_plate.in -var x0 "${plate[0]}" -var y0 "${plate[1]}" \
  -var y1 "${plate[2]}" -var z0 "${plate[3]}" -var z1 "${plate[4]}"

echo "| code | phase | steps | stepping [s] | particle-steps/s per core | peak memory, all ranks [MB] | particles | bed height [m] | packing fraction | kinetic energy [J] | height, packing vs ours |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for phase in settle settled; do
  steps=$([[ $phase == settle ]] && echo "$settle" || echo "$settled")
  IFS=, read -r _ h0 p0 _ <<< "${state[gpudem.$phase]}"
  for code in $settling_codes; do
    IFS=, read -r n h p ke <<< "${state[$code.$phase]}"
    awk -v c="$code" -v ph="$phase" -v st="$steps" -v s="${seconds[$code.$phase]}" \
      -v r="$ranks" -v m="${memory[$code.$phase]}" -v n="$n" -v h="$h" -v p="$p" -v ke="$ke" \
      -v h0="$h0" -v p0="$p0" 'BEGIN {
        printf "| %s | %s | %d | %.3g | %.3g | %s | %d | %.4f | %.4f | %.3g | %+.1f %%, %+.1f %% |\n",
          c, ph, st, s, n * st / s / r, m, n, h, p, ke, 100 * (h / h0 - 1), 100 * (p / p0 - 1) }'
  done
done

echo
echo "Plate drag: $drag steps at $speed m/s from gpudem-mpi's settled bed ($(cat "$out/gpudem/plate/slot.log"))"
echo "| code | steps | stepping [s] | particle-steps/s per core | peak memory, all ranks [MB] | particles | draft over the second half, mean ± std [N] | mean vs ours |"
echo "|---|---|---|---|---|---|---|---|"
IFS=, read -r _ f0 _ <<< "${force[gpudem]}"
for code in gpudem liggghts lammps; do
  IFS=, read -r _ f s <<< "${force[$code]}"
  awk -v c="$code" -v st="$drag" -v sec="${seconds[$code.plate]}" -v r="$ranks" \
    -v m="${memory[$code.plate]}" -v n="${counts[$code]}" -v f="$f" -v s="$s" -v f0="$f0" 'BEGIN {
      printf "| %s | %d | %.3g | %.3g | %s | %d | %.1f ± %.1f | %+.1f %% |\n",
        c, st, sec, n * st / sec / r, m, n, -f, s, 100 * (f / f0 - 1) }'
done
