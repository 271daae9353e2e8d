#!/usr/bin/env bash
# Installs the Debian 12 packages gpudem-mpi needs (skipped when all are present) and builds it
# and the benchmarks into ./build (the tests: scripts/test.sh). The CUDA backend is built when
# nvcc is found (CUDA toolkit, not from Debian).
# Usage: scripts/setup.sh [PACKAGE ...]: further Debian packages to install when missing (the
# peer codes of the comparison scripts: liggghts, lammps).
# Environment: BUILD_DIR (default build), GPUDEM_CMAKE_ARGS (extra cmake arguments),
# GPUDEM_SETUP_TARGET (build only this target instead of all).
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake ninja-build pkg-config libopenmpi-dev openmpi-bin
          libhdf5-openmpi-dev hdf5-tools libmetis-dev libcli11-dev libgtest-dev libtoml11-dev
          python3 python3-h5py python3-numpy python3-scipy python3-matplotlib xz-utils "$@")

scripts/install-packages.sh "${packages[@]}"

BUILD_DIR=${BUILD_DIR:-build}
# Ninja compiles a library's sources while the libraries it links are still being built, which
# keeps both cores busy; a build directory made earlier keeps its generator.
generator=()
[[ -f $BUILD_DIR/CMakeCache.txt ]] || generator=(-G Ninja)
cmake -S . -B "$BUILD_DIR" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release ${GPUDEM_CMAKE_ARGS:-}
cmake --build "$BUILD_DIR" ${GPUDEM_SETUP_TARGET:+--target "$GPUDEM_SETUP_TARGET"} -j "$(nproc)"
