#!/usr/bin/env bash
# Submits JOBS copies of scripts/slurm/gpudem.sbatch for one run, each starting once the one
# before it has ended (--dependency=afterany), so that a run longer than the time limit of one
# job goes on from its latest checkpoint in the next; the jobs left once it is complete end at
# once. Prints the job ids.
# Usage: scripts/slurm/submit_chain.sh JOBS SCENE [gpudem-mpi options]
#   SBATCH_ARGS  options for every sbatch call, e.g. "--nodes=4 --time=24:00:00 --account=p1"
#   (OUT, GPUDEM and BACKEND reach the jobs through sbatch's environment, as for gpudem.sbatch)
set -euo pipefail
if [[ $# -lt 2 || ! $1 =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: $0 JOBS SCENE [gpudem-mpi options] (JOBS a positive integer)" >&2
  exit 2
fi
jobs=$1
shift
template="$(cd "$(dirname "$0")" && pwd)/gpudem.sbatch"
read -r -a options <<< "${SBATCH_ARGS:-}"
previous=""
for ((n = 1; n <= jobs; ++n)); do
  after=()
  [[ -n $previous ]] && after=(--dependency="afterany:$previous")
  previous=$(sbatch --parsable "${options[@]}" "${after[@]}" "$template" "$@")
  previous=${previous%%;*}  # "id;cluster" on federated clusters
  echo "$previous"
done
