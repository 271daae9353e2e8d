#!/usr/bin/env bash
# Sets up and builds gpudem-mpi (scripts/setup.sh), builds the tests (target gpudem_tests) and
# runs the whole test suite (host backend).
#
# Usage: scripts/test.sh [--sanitize [--subset]] [CTEST_ARGUMENT ...]
#   --sanitize  build into build-sanitize/ instead (host backend, AddressSanitizer with
#               LeakSanitizer, and UndefinedBehaviorSanitizer, at -O1 with assertions on) and
#               run the suite there: any report fails its test
#   --subset    with --sanitize, only the tests labelled sanitize (the subset CI runs, listed
#               in tests/CMakeLists.txt) and the executables they need
# Further arguments go to ctest (e.g. -R scene_loader).
# Environment: BUILD_DIR (default build, or build-sanitize), CTEST_PARALLEL (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."

sanitize=0
subset=0
while (($#)); do
  case $1 in
    --sanitize) sanitize=1; shift ;;
    --subset) subset=1; shift ;;
    *) break ;;
  esac
done
if ((subset && !sanitize)); then
  echo "test.sh: --subset goes with --sanitize" >&2
  exit 2
fi

targets=(gpudem_tests)
if ((sanitize)); then
  export BUILD_DIR=${BUILD_DIR:-build-sanitize}
  export GPUDEM_CMAKE_ARGS="${GPUDEM_CMAKE_ARGS:-} -DCMAKE_BUILD_TYPE=Debug -DGPUDEM_ENABLE_CUDA=OFF -DGPUDEM_SANITIZE=ON"
  export GPUDEM_SETUP_TARGET=gpudem-mpi
  # Open MPI's own allocations at MPI_Init are suppressed by library name
  # (cmake/sanitize/lsan-suppressions.txt); every other leak, overflow or undefined
  # operation stops the program.
  export LSAN_OPTIONS="suppressions=$PWD/cmake/sanitize/lsan-suppressions.txt:print_suppressions=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:strict_init_order=1"
  # hwloc's GL and OpenCL plugins, which Open MPI's MPI_Init loads to map the node, bring in
  # X11 and OpenCL libraries whose dynamic thread-local storage LeakSanitizer's scan at exit
  # cannot read (it stops with "Tracer caught signal 11"); the solver uses neither.
  export HWLOC_COMPONENTS=-gl,-opencl
fi
# Debian's Slurm for the test that runs the batch scripts under it (slurm_real)
scripts/setup.sh slurm-wlm
((subset)) && targets=(gpudem_sanitize_subset)
cmake --build "${BUILD_DIR:-build}" --target "${targets[@]}" -j "$(nproc)"
source scripts/mpi-env.sh
# Two tests at a time, one OpenMP thread each, on a 2-core machine.
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
cd "${BUILD_DIR:-build}"
labels=()
((subset)) && labels=(-L '^sanitize$')
ctest --output-on-failure -j "${CTEST_PARALLEL:-2}" "${labels[@]}" "$@"
