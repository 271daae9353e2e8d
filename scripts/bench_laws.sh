#!/usr/bin/env bash
# Cost of each contact-law slot on the same settled 10^5 bed, 1 and 2 threads.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
build/bench/gpudem-bench-laws
