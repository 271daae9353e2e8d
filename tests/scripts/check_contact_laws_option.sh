#!/usr/bin/env bash
# The CMake option GPUDEM_CONTACT_LAWS (src/core/contact_model.cmake), configured for real in a
# scratch build tree (host only, no tests): a restricted list becomes the patterns of the
# generated CompiledContactLaws.hpp; a name that is no choice of its slot, a pattern without
# five parts and an empty list stop the configuration with a message naming them.
# Usage: check_contact_laws_option.sh SOURCE_DIR WORK_DIR
set -uo pipefail
source_dir=$1
work=$2
failures=0
configure() {  # configure LAWS -> output in $work/log (lines joined: CMake wraps messages)
  rm -rf "$work/build"
  cmake -S "$source_dir" -B "$work/build" -DGPUDEM_ENABLE_CUDA=OFF -DGPUDEM_BUILD_TESTS=OFF \
    "-DGPUDEM_CONTACT_LAWS=$1" > "$work/raw.log" 2>&1
  local status=$?
  tr -s ' \n' ' ' < "$work/raw.log" > "$work/log"
  return $status
}
expect() {  # expect WHAT CONDITION...
  local what=$1
  shift
  if ! "$@"; then
    echo "FAIL: $what"
    failures=$((failures + 1))
  fi
}
mkdir -p "$work"

configure 'hertz/restitution/mindlin/*/none;hooke/none/none/none/sjkr'
expect "a valid list configures" test $? -eq 0
header="$work/build/src/generated/core/CompiledContactLaws.hpp"
expect "the patterns are written as slot indices" \
  grep -q 'GPUDEM_CONTACT_LAW_PATTERNS {{1, 1, 2, -1, 0}}, {{0, 0, 0, 0, 1}},' "$header"

configure 'hertz/restitution/coulomb/*/none'
expect "an unknown tangential law stops the configuration" test $? -ne 0
expect "the message names it and the slot" grep -q "'coulomb' in 'hertz/restitution/coulomb/\*/none' is not a tangential law" "$work/log"

configure 'hertz/restitution/mindlin'
expect "a pattern of three parts stops the configuration" test $? -ne 0
expect "the message names the pattern" grep -q "'hertz/restitution/mindlin' is not normal/damping/tangential/rolling/cohesion" "$work/log"

configure ''
expect "an empty list stops the configuration" test $? -ne 0
expect "the message says it is empty" grep -q "GPUDEM_CONTACT_LAWS is empty" "$work/log"

rm -rf "$work"
echo "check_contact_laws_option: $failures failure(s)"
[[ $failures -eq 0 ]]
