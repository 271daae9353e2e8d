#!/usr/bin/env bash
# Fuzzes the input readers with libFuzzer under AddressSanitizer and UndefinedBehaviorSanitizer:
# the scene reader, the STL reader, the CSV particle reader and the checkpoint/bed reader
# (tests/fuzz/). Installs clang, builds the targets into build-fuzz/ (clang, host backend), runs
# each reader for SECONDS from its corpus, and merges the inputs that reached new code into
# tests/fuzz/corpus/<reader>/, which the ctests fuzz_corpus_* replay in every build.
#
# Usage: scripts/fuzz.sh [--seconds S] [--jobs J] [READER ...]
#   READER   scene, stl, csv, checkpoint (default: all four)
#   S        seconds of fuzzing per reader (default 600; 0: only build the targets)
#   J        readers fuzzed at once, one core each (default 1)
# A finding (crash, sanitizer report, leak, input slower than 10 s) stops its reader; the
# input is kept as build-fuzz/findings/<reader>/crash-* (or leak-*, timeout-*) and the script
# exits 1. The working corpora in build-fuzz/corpus/ persist, so a later run continues.
# Environment: FUZZ_BUILD_DIR (default build-fuzz).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=600
jobs=1
readers=()
while (($#)); do
  case $1 in
    --seconds) seconds=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    scene|stl|csv|checkpoint) readers+=("$1"); shift ;;
    *) echo "fuzz.sh: unknown argument '$1' (readers: scene stl csv checkpoint)" >&2; exit 2 ;;
  esac
done
((${#readers[@]})) || readers=(scene stl csv checkpoint)
[[ $seconds =~ ^[0-9]+$ && $jobs =~ ^[1-9][0-9]*$ ]] ||
  { echo "fuzz.sh: --seconds and --jobs take whole numbers" >&2; exit 2; }

scripts/install-packages.sh build-essential cmake ninja-build clang-14 libclang-rt-14-dev \
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libmetis-dev libcli11-dev libgtest-dev \
  libtoml11-dev
build=${FUZZ_BUILD_DIR:-build-fuzz}
[[ -f $build/build.ninja ]] ||
  CC=clang-14 CXX=clang++-14 cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DGPUDEM_ENABLE_CUDA=OFF -DGPUDEM_ENABLE_OPENMP=OFF -DGPUDEM_FUZZ=ON
cmake --build "$build" --target fuzz_targets -j "$(nproc)"
((seconds > 0)) || exit 0

# The inputs a reader's corpus starts from besides its stored corpus.
seeds() {
  case $1 in
    scene) find inputs tests/data/scenes -name '*.toml' ;;
    stl) find inputs -name '*.stl' -size -64k ;;
    csv) find inputs tests/data/csv -name '*.csv' -size -64k ;;
    checkpoint) ;;
  esac
}

# Fuzzes one reader for $seconds, then merges what it found into the stored corpus.
fuzz_reader() {
  local reader=$1 work=$build/corpus/$1 findings=$build/findings/$1/
  local stored=tests/fuzz/corpus/$1
  mkdir -p "$work" "$findings" "$stored"
  cp -n "$stored"/* "$work"/ 2>/dev/null || true
  seeds "$reader" | while read -r f; do cp -n "$f" "$work/seed-$(basename "$f")"; done
  echo "fuzz.sh: $reader for ${seconds} s (log $build/$reader.log)"
  local status=0
  "$build/tests/fuzz_$reader" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
    -max_len=65536 -print_final_stats=1 -artifact_prefix="$findings" "$work" \
    > "$build/$reader.log" 2>&1 || status=$?
  grep -E '^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss_mb)' "$build/$reader.log" |
    sed "s/^/fuzz.sh: $reader: /" || true
  if ((status)); then
    echo "fuzz.sh: $reader: FINDING, see $build/$reader.log and $findings" >&2
    return 1
  fi
  "$build/tests/fuzz_$reader" -merge=1 "$stored" "$work" > "$build/$reader.merge.log" 2>&1
  echo "fuzz.sh: $reader: no finding; stored corpus $stored: $(ls "$stored" | wc -l) input(s)"
}

failed=0
running=0
for reader in "${readers[@]}"; do
  if ((running == jobs)); then
    wait -n || failed=1
    running=$((running - 1))
  fi
  fuzz_reader "$reader" &
  running=$((running + 1))
done
while ((running)); do
  wait -n || failed=1
  running=$((running - 1))
done
exit $failed
