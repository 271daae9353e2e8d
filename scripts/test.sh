#!/usr/bin/env bash
# Sets up and builds gpudem-mpi (scripts/setup.sh), builds the tests (target gpudem_tests) and
# runs the whole test suite (host backend).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --build "${BUILD_DIR:-build}" --target gpudem_tests -j "$(nproc)"
source scripts/mpi-env.sh
# Two tests at a time, one OpenMP thread each, on a 2-core machine.
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
cd "${BUILD_DIR:-build}"
ctest --output-on-failure -j "${CTEST_PARALLEL:-2}"
