#!/usr/bin/env bash
# Runs on the GPU machine, from the repository root, with the bundle that scripts/gpu_bundle.sh
# made (gpu-bundle/gpudem-gpu.tar.xz, carried there): checks and measurements of the CUDA
# backend. Under $OUT (default out/gpu_check) it leaves few files, refreshed after each part:
# summary.txt (also printed last), device.txt, bench_soil.md and logs.tar.gz (every log).
#   mps        starts the CUDA Multi-Process Service for the parts after it, up to the
#              sanitizer (processes that share the GPU then run side by side rather than in
#              turns); stopped at the end
#   tests      the whole test suite as ctest runs it (gpu-bundle/tests.sh), one test per 4 cores
#              at a time (4 on the 16-core GPU machines), one OpenMP thread per rank
#   sanitizer  compute-sanitizer memcheck (1 and 2 ranks) and racecheck (1 rank) on short
#              runs of the tool scene (Hertz–Mindlin, rolling, walls, a mesh) and a periodic gas
#   bench      gpudem-bench-soil on the CUDA backend: settled soil beds of 10^5, 10^6 and
#              10^7 spheres in each precision, and the largest mixed bed that fits
#   split      gpudem-mpi --exact-time-split on the benchmarks' settled 10^6 bed
#              (scripts/bench_scene.sh), 500 steps with a snapshot every 50, on 1, 2 and 4
#              ranks sharing the GPU: integration, forces, neighbour lists, halo, output; and on
#              1 rank with lean snapshots (velocity and id in float)
# Usage: scripts/gpu_check.sh PART... (default: mps tests sanitizer)
# Environment: OUT (results), BENCH_ARGS (replace the bench's default arguments), PYTHON (a
# Python 3 with h5py and numpy, default python3), TESTS (an extended regular expression: only
# the tests whose whole name it matches, e.g. 'test_settling|mpi_.*'; default all), FIRST (a
# regular expression: the tests it matches start first; default the host-versus-CUDA
# comparisons, the CUDA unit tests, the hard cases on CUDA, precision and the rank-count runs),
# BUDGET (seconds for all parts, default 480, so that one device call of 540 s holds them: every
# command is stopped when the budget runs out, and what it did not reach is listed as such),
# TESTS_AT_ONCE (tests side by side, default one per 4 cores), WORK (scratch, default
# /tmp/gpudem-work), BUNDLE (where the bundle is unpacked, default /tmp/gpudem-gpu).
set -uo pipefail
cd "$(dirname "$0")/.."
SRC=$PWD
OUT=${OUT:-$SRC/out/gpu_check}
WORK=${WORK:-/tmp/gpudem-work}
BUNDLE=${BUNDLE:-/tmp/gpudem-gpu}
PYTHON=${PYTHON:-python3}
TESTS=${TESTS:-.*}
FIRST=${FIRST:-mpi_cuda|test_backend_agreement|.*_cuda|hard_cuda_.*|test_portable_cuda|test_precision|mpi_.*}
BUDGET=${BUDGET:-480}
LOGS=$WORK/logs
rm -rf "$LOGS"
mkdir -p "$OUT" "$WORK" "$LOGS"
summary=()

# Leaves the summary so far and every log under $OUT, so that a run cut short still reports.
publish() {
  printf '%s\n' "${summary[@]}" > "$OUT/summary.txt"
  tar -C "$WORK" --warning=no-file-changed -czf "$WORK/logs.tar.gz.part" logs &&
    mv "$WORK/logs.tar.gz.part" "$OUT/logs.tar.gz"
}

# Unpacks the carried bundle afresh (a warm machine may hold an older one).
unpack() {
  [ -f gpu-bundle/gpudem-gpu.tar.xz ] || { echo "gpu_check: gpu-bundle/gpudem-gpu.tar.xz missing (scripts/gpu_bundle.sh, then carry gpu-bundle)" >&2; exit 2; }
  rm -rf "$BUNDLE"
  tar -C "$(dirname "$BUNDLE")" -xJf gpu-bundle/gpudem-gpu.tar.xz
}

describe_device() {
  { date -u; cat gpu-bundle/commit
    nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv
    nproc; } > "$OUT/device.txt" 2>&1
  summary+=("device: $(nvidia-smi --query-gpu=name --format=csv,noheader 2>/dev/null | head -1), bundle of $(paste -sd ' ' gpu-bundle/commit)")
}

# Seconds left of the budget, at least 1 (bash counts SECONDS from the start, in subshells too).
left() { local l=$(( BUDGET - SECONDS )); echo $(( l > 1 ? l : 1 )); }

# within LIMIT: the smaller of LIMIT and the seconds left.
within() { local l; l=$(left); echo $(( $1 < l ? $1 : l )); }

# run_test NAME TIMEOUT SKIP_CODE [VAR=VALUE...] -- COMMAND...: one line of gpu-bundle/tests.sh.
run_test() {
  local name=$1 limit=$2 skip=$3
  shift 3
  local env=()
  while [ "$1" != "--" ]; do env+=("$1"); shift; done
  shift
  local log="$LOGS/tests/$name.log" rc cut=false
  [ "$(left)" -le "$limit" ] && cut=true
  (cd "$WORK" && env "${env[@]}" timeout "$(within "$limit")" "$@") > "$log" 2>&1
  rc=$?
  if [ $rc -eq 0 ]; then echo "passed $name" >> "$LOGS/tests/results"
  elif [ $rc -eq "$skip" ]; then echo "skipped $name" >> "$LOGS/tests/results"
  elif [ $rc -eq 124 ] && $cut; then echo "cut $name (the budget ran out)" >> "$LOGS/tests/results"
  else echo "FAILED $name (exit $rc)" >> "$LOGS/tests/results"; fi
}

part_tests() {
  mkdir -p "$LOGS/tests"
  : > "$LOGS/tests/results"
  local at_once=${TESTS_AT_ONCE:-$(( $(nproc) / 4 > 1 ? $(nproc) / 4 : 1 ))}
  export OMP_NUM_THREADS=1  # as scripts/test.sh: ranks and tests share the cores
  export GPUDEM_SOURCE_DIR=$SRC GPUDEM_BINARY=$BUNDLE/bin/gpudem-mpi GPUDEM_MPIEXEC=mpirun
  export GPUDEM_SNAPSHOT_FIXTURE_DIR=$WORK/snapshot_fixture PYTHON
  local lines line fixture='^run_test test_snapshot_writer |snapshot_fixture'
  # The tests FIRST names lead, the others follow in ctest's order.
  mapfile -t lines < <(awk -v names="^($TESTS)\$" -v first="^($FIRST)\$" '
    $1 == "run_test" && $2 ~ names { if ($2 ~ first) print; else later[n++] = $0 }
    END { for (i = 0; i < n; ++i) print later[i] }' gpu-bundle/tests.sh)
  # The snapshot fixture's writer and readers in order, then the rest, one test per 4 cores.
  for line in "${lines[@]}"; do [[ $line =~ $fixture ]] && eval "$line"; done
  for line in "${lines[@]}"; do
    [[ $line =~ $fixture ]] && continue
    while [ "$(jobs -rp | wc -l)" -ge "$at_once" ]; do wait -n; publish; done
    if [ "$(left)" -le 5 ]; then
      echo "not reached $(awk '{ print $2 }' <<< "$line")" >> "$LOGS/tests/results"
      continue
    fi
    eval "$line" &
  done
  wait
  # GoogleTest's own count of the cases that skipped inside a passing executable.
  local skipped failed
  skipped=$(grep -h "^\[  SKIPPED \] [A-Za-z]" "$LOGS"/tests/*.log | sort -u | wc -l)
  local results=$LOGS/tests/results
  summary+=("tests: $(grep -c '^passed' "$results") passed, $(grep -c '^skipped' "$results") skipped, $(grep -c '^FAILED' "$results") failed, $(grep -cE '^(cut|not reached)' "$results") cut or not reached by the budget; $skipped GoogleTest cases skipped inside them")
  mapfile -t failed < <(grep -E '^(FAILED|cut|not reached)' "$results")
  for line in "${failed[@]}"; do summary+=("  $line"); done
}

# sanitize TOOL RANKS SCENE END_TIME: one compute-sanitizer run, its verdict into the summary.
sanitize() {
  local tool=$1 ranks=$2 scene=$3 end=$4
  local name="$tool-np$ranks-$(basename "$scene" .toml)" rc
  if [ "$(left)" -le 20 ]; then summary+=("sanitizer $name: not reached (budget)"); return; fi
  timeout "$(left)" mpirun -np "$ranks" compute-sanitizer --tool "$tool" --error-exitcode 99 --print-limit 20 \
    "$BUNDLE/bin/gpudem-mpi" "$scene" --backend cuda --set simulation.end_time="$end" \
    --output-dir "$WORK/$name" --quiet > "$LOGS/sanitizer/$name.log" 2>&1
  rc=$?
  summary+=("sanitizer $name: exit $rc, $(grep -hE 'ERROR SUMMARY|RACECHECK SUMMARY' "$LOGS/sanitizer/$name.log" | sort | uniq -c | tr -s ' ' | paste -sd ';')")
}

part_sanitizer() {
  stop_mps
  mkdir -p "$LOGS/sanitizer"
  local tool=$SRC/tests/mpi/scenes/tool.toml gas=$SRC/tests/mpi/scenes/periodic_gas.toml
  sanitize memcheck 1 "$tool" 0.004
  sanitize memcheck 2 "$tool" 0.004
  sanitize memcheck 1 "$gas" 0.004
  sanitize racecheck 1 "$tool" 0.001
}

# Starts the CUDA Multi-Process Service, so that the processes sharing the GPU (tests run side
# by side, ranks) run their kernels concurrently instead of taking turns in time slices; stops it
# again if a CUDA run then fails. Under MPS a fatal fault in one process ends the others on the
# GPU too: a test that fails alone shows in its own log.
mps_started=false
part_mps() {
  local log=$LOGS/mps.log
  if ! command -v nvidia-cuda-mps-control > /dev/null; then
    summary+=("mps: nvidia-cuda-mps-control not found, the processes take turns on the GPU")
    return
  fi
  export CUDA_MPS_PIPE_DIRECTORY=$WORK/mps-pipe CUDA_MPS_LOG_DIRECTORY=$WORK/mps-log
  mkdir -p "$CUDA_MPS_PIPE_DIRECTORY" "$CUDA_MPS_LOG_DIRECTORY"
  nvidia-cuda-mps-control -d > "$log" 2>&1 && mps_started=true
  if "$BUNDLE/bin/gpudem-mpi" "$SRC/tests/mpi/scenes/tool.toml" --backend cuda --quiet \
      --set simulation.end_time=0.0005 --output-dir "$WORK/mps-probe" >> "$log" 2>&1; then
    summary+=("mps: on")
  else
    stop_mps
    summary+=("mps: a CUDA run failed under it (logs/mps.log), stopped")
  fi
}

# Stops the MPS daemon this script started (at the end, and before the sanitizer, which runs
# without it).
stop_mps() {
  if $mps_started; then
    echo quit | nvidia-cuda-mps-control >> "$LOGS/mps.log" 2>&1
    mps_started=false
  fi
}
trap stop_mps EXIT

part_bench() {
  local args=${BENCH_ARGS:---backend cuda --sizes 1e5,1e6,1e7 --precisions mixed,double,float --largest}
  # shellcheck disable=SC2086
  timeout "$(left)" "$BUNDLE/bin/gpudem-bench-soil" $args > "$OUT/bench_soil.md" 2>&1
  summary+=("bench: exit $?, $OUT/bench_soil.md")
  summary+=("$(grep '^|' "$OUT/bench_soil.md")")
}

part_split() {
  mkdir -p "$WORK/split/build/bench"
  ln -sf "$BUNDLE/bin/gpudem-bench-write-bed" "$WORK/split/build/bench/"
  source scripts/bench_scene.sh
  write_bench_scene "$WORK/split/build" "$WORK/split" 6 > "$LOGS/split.log" 2>&1
  local dt end every ranks
  dt=$("$BUNDLE/bin/gpudem-mpi" "$WORK/split/scene.toml" --check | sed -n 's/^dt = \([^ ]*\) s.*/\1/p')
  end=$(awk -v dt="$dt" 'BEGIN { printf "%.17g", dt * 500 }')
  every=$(awk -v dt="$dt" 'BEGIN { printf "%.17g", dt * 50 }')
  local run settings
  for run in 1 2 4 1-lean; do
    ranks=${run%-lean}
    settings=()
    [ "$run" != "$ranks" ] &&
      settings=(--set 'output.precision="float"' --set 'output.fields=["velocity","id"]')
    echo "== $run rank(s)" >> "$LOGS/split.log"
    OMP_NUM_THREADS=$(( $(nproc) / ranks )) timeout "$(left)" \
      mpirun -np "$ranks" "$BUNDLE/bin/gpudem-mpi" "$WORK/split/scene.toml" --backend cuda \
      --exact-time-split --set simulation.end_time="$end" --set output.every="$every" \
      --set "decomposition.dims=[$ranks,1,1]" --output-dir "$WORK/split/n$run" \
      "${settings[@]}" >> "$LOGS/split.log" 2>&1
    summary+=("split, $run rank(s): exit $?")
  done
  mapfile -t lines < <(grep -E "^(== |time split|done)" "$LOGS/split.log")
  summary+=("${lines[@]}")
}

parts=("$@")
[ ${#parts[@]} -gt 0 ] || parts=(mps tests sanitizer)
for part in "${parts[@]}"; do
  case $part in
    mps | tests | sanitizer | bench | split) ;;
    *) echo "gpu_check: unknown part '$part' (mps, tests, sanitizer, bench, split)" >&2; exit 2 ;;
  esac
done
unpack
source "$BUNDLE/env.sh"
export PATH=$PATH:/usr/local/cuda/bin  # compute-sanitizer
describe_device
for part in "${parts[@]}"; do
  if [ "$(left)" -le 10 ]; then summary+=("$part: not reached (budget)"); continue; fi
  "part_$part"
  publish
done
publish
cat "$OUT/summary.txt"
