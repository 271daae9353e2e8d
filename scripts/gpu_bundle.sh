#!/usr/bin/env bash
# Builds the CUDA backend for one GPU architecture, with shared libraries so that the test and
# benchmark executables share one copy of the engines' device code, and packs what
# scripts/gpu_check.sh runs on a GPU machine into gpu-bundle/ (ignored by git; name it as a
# carried path):
#   gpu-bundle/gpudem-gpu.tar.xz  gpudem-mpi, the test executables and the benchmarks
#                                 (gpudem-bench-soil, gpudem-bench-write-bed) with their
#                                 libraries, Open MPI included (../shared/gpu-node/bundle.sh)
#   gpu-bundle/tests.sh           the test suite's commands, paths made the bundle's
#                                 (scripts/gpu_manifest.py)
#   gpu-bundle/commit             the commit built, and whether the tree had changes
# Usage: scripts/gpu_bundle.sh [ARCH (default 90)]
# Environment: BUILD_DIR (default build-gpu).
set -euo pipefail
cd "$(dirname "$0")/.."
arch=${1:-90}
build=${BUILD_DIR:-build-gpu}
bundler=../shared/gpu-node/bundle.sh
[ -x "$bundler" ] || { echo "gpu_bundle: $bundler not found" >&2; exit 2; }
BUILD_DIR=$build GPUDEM_CMAKE_ARGS="-DGPUDEM_ENABLE_CUDA=ON -DCMAKE_CUDA_ARCHITECTURES=$arch \
-DGPUDEM_LIBRARY_TYPE=SHARED" scripts/setup.sh
cmake --build "$build" --target gpudem_tests -j "$(nproc)"
mkdir -p gpu-bundle
python3 scripts/gpu_manifest.py "$build" . gpu-bundle/tests.sh
mapfile -t tests < gpu-bundle/tests.sh.executables
rm gpu-bundle/tests.sh.executables
"$bundler" gpu-bundle/gpudem-gpu "$build/gpudem-mpi" "$build/bench/gpudem-bench-soil" \
  "$build/bench/gpudem-bench-write-bed" "${tests[@]}"
rm -rf gpu-bundle/gpudem-gpu  # the archive travels
{ git log -1 --format='commit %H (%cd)'
  git diff --quiet HEAD -- && echo "tree as committed" || echo "tree with uncommitted changes"
} > gpu-bundle/commit
du -h gpu-bundle/gpudem-gpu.tar.xz
