#!/usr/bin/env bash
# Host-backend throughput on settled beds of 10^4, 10^5 and 10^6 particles at 1 and 2 threads,
# in double and in mixed precision (with the force error of mixed against double).
# Usage: scripts/bench_host.sh [max_exponent (4..6, default 6)]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
build/bench/gpudem-bench-host "${1:-6}"
