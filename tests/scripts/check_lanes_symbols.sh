#!/usr/bin/env bash
# The objects built for x86-64-v4 (engine/PairLanesInstance.in, engine/NeighborSlotsAvx512.cpp)
# must define no global symbol but the AVX-512 sweeps and the neighbour search's slot test: any
# other (an inline function emitted out of line, a template instantiation) could be the copy the
# linker keeps for the generic code too, and stop a CPU without AVX-512 with an illegal
# instruction.
# usage: check_lanes_symbols.sh OBJECT...
set -euo pipefail
(($#)) || { echo "usage: check_lanes_symbols.sh OBJECT..." >&2; exit 2; }
sweeps=0
slot_tests=0
others=()
while IFS= read -r line; do
  symbol=${line#* ? }
  if [[ $symbol == "void gpudem::sweep_in_avx512_lanes<"* ]]; then
    sweeps=$((sweeps + 1))
  elif [[ $symbol == "gpudem::slots_within_avx512("* ]]; then
    slot_tests=$((slot_tests + 1))
  else
    others+=("$line")
  fi
done < <(nm -C --defined-only --extern-only "$@" | grep -E '^[0-9a-f]+ [A-Za-z] ')
if ((${#others[@]})); then
  echo "defined besides the sweeps and the slot test in $*:" >&2
  printf '  %s\n' "${others[@]}" >&2
  exit 1
fi
if ((sweeps == 0)); then
  echo "no sweep_in_avx512_lanes defined in $*" >&2
  exit 1
fi
if ((slot_tests != 1)); then
  echo "slots_within_avx512 defined $slot_tests times in $*" >&2
  exit 1
fi
echo "$sweeps sweeps and the slot test, nothing else"
