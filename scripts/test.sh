#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (host backend).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/mpi-env.sh
# Two tests at a time, one OpenMP thread each, on a 2-core machine.
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
cd "${BUILD_DIR:-build}"
ctest --output-on-failure -j "${CTEST_PARALLEL:-2}"
