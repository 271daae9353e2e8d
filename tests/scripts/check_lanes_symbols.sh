#!/usr/bin/env bash
# The objects built for x86-64-v4 or x86-64-v3 (engine/PairLanesInstance.in,
# engine/NeighborSlotsAvx512.cpp, engine/NeighborSlotsAvx2.cpp) must define no global symbol but
# their sweeps in lanes and one other function (the neighbour search's slot test): any other (an
# inline function emitted out of line, a template instantiation) could be the copy the linker
# keeps for the generic code too, and stop a CPU without those instructions with an illegal
# instruction.
# usage: check_lanes_symbols.sh SWEEP OTHER OBJECT...
#   SWEEP: the sweeps' function template (sweep_in_avx512_lanes); OTHER: the one function
#   besides them, defined once (slots_within_avx512).
set -euo pipefail
(($# >= 3)) || { echo "usage: check_lanes_symbols.sh SWEEP OTHER OBJECT..." >&2; exit 2; }
sweep=$1 other=$2
shift 2
sweeps=0
others=0
strays=()
while IFS= read -r line; do
  symbol=${line#* ? }
  if [[ $symbol == "void gpudem::$sweep<"* ]]; then
    sweeps=$((sweeps + 1))
  elif [[ $symbol == "gpudem::$other("* ]]; then
    others=$((others + 1))
  else
    strays+=("$line")
  fi
done < <(nm -C --defined-only --extern-only "$@" | grep -E '^[0-9a-f]+ [A-Za-z] ')
if ((${#strays[@]})); then
  echo "defined besides $sweep and $other in $*:" >&2
  printf '  %s\n' "${strays[@]}" >&2
  exit 1
fi
if ((sweeps == 0)); then
  echo "no $sweep defined in $*" >&2
  exit 1
fi
if ((others != 1)); then
  echo "$other defined $others times in $*" >&2
  exit 1
fi
echo "$sweeps sweeps and $other, nothing else"
