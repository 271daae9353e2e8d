#!/usr/bin/env bash
# scripts/slurm/ under Debian's Slurm (slurm-wlm), started for real on this machine: a
# controller and one node with this machine's cores, no GPUs, in WORK_DIR. submit_chain.sh
# submits five one-minute jobs of gpudem.sbatch (2 ranks, host backend) for a run that needs
# about 150 s: the first job hits its time limit and is cancelled by Slurm (Slurm checks
# the limits every 30 s, so at 60 to 95 s), the next ones resume from the checkpoint, the last
# ones find the run complete (four jobs step at least 4 x 57 s, so the run may take 100 to
# 220 s: the speed measured below may be off by a third either way). The run's
# final checkpoint and time series must then equal, bit for bit, those of the same scene run
# straight through with mpirun. Slurm is stopped on exit, whatever happened.
# Exit 77 (skipped, with the reason) where Slurm is missing or does not start.
# Usage: check_slurm_real.sh SOURCE_DIR GPUDEM_BINARY MPIRUN WORK_DIR
set -euo pipefail
source_dir=$1 binary=$2 mpirun=$3 work=$4
skip() {
  echo "SKIPPED: $*"
  exit 77
}
for tool in slurmctld slurmd sbatch squeue sinfo scancel h5diff; do
  command -v "$tool" > /dev/null || skip "$tool not found (Debian's slurm-wlm and hdf5-tools)"
done
[[ $(id -u) -eq 0 ]] || skip "slurmd starts jobs as their user only when run as root"
cores=$(getconf _NPROCESSORS_ONLN)  # not nproc, which follows OMP_NUM_THREADS
((cores >= 2)) || skip "the jobs take 2 cores; this machine has $cores"

for daemon in slurmd slurmctld; do  # left running by an earlier run that was killed
  [[ -f $work/$daemon.pid ]] && kill "$(cat "$work/$daemon.pid")" 2> /dev/null || true
done
rm -rf "$work"
mkdir -p "$work/state" "$work/spool" "$work/log"
work=$(cd "$work" && pwd)
node=$(hostname -s)
export SLURM_CONF=$work/slurm.conf
cat > "$SLURM_CONF" <<CONF
ClusterName=gpudemtest
SlurmctldHost=$node
SlurmctldPort=26817
SlurmdPort=26818
SlurmUser=root
SlurmdUser=root
AuthType=auth/none
CredType=cred/none
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=pmix
ReturnToService=2
KillWait=5
MinJobAge=600
InactiveLimit=0
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$node CPUs=$cores State=UNKNOWN
PartitionName=gpu Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF

stop_slurm() {
  scancel --user=root > /dev/null 2>&1 || true
  for daemon in slurmd slurmctld; do
    [[ -f $work/$daemon.pid ]] && kill "$(cat "$work/$daemon.pid")" 2> /dev/null || true
  done
}
trap stop_slurm EXIT
slurmctld -i -f "$SLURM_CONF" || skip "slurmctld did not start: $(tail -n 3 "$work/log/slurmctld.log")"
slurmd -f "$SLURM_CONF" || skip "slurmd did not start: $(tail -n 3 "$work/log/slurmd.log")"
for ((wait = 0; wait < 30; ++wait)); do
  [[ $(sinfo -h -o %T 2> /dev/null) == idle ]] && break
  sleep 1
done
[[ $(sinfo -h -o %T 2> /dev/null) == idle ]] ||
  skip "the node did not come up: $(tail -n 3 "$work/log/slurmctld.log" "$work/log/slurmd.log")"

# The 200 grains of the stand-in test (slurm_scene.toml), a checkpoint every second of simulated
# time; end_time is set below so that the run steps for about 150 s on 2 ranks here.
cp "$source_dir/tests/scripts/slurm_scene.toml" "$work/scene.toml"
settings=(--set checkpoint.every=1.0 --set output.timeseries_every=0.5 --set output.every=1000.0)

for v in $(env | grep -Eo '^(OMPI|PMIX|OPAL)_[A-Za-z0-9_]*'); do unset "$v"; done
source "$source_dir/scripts/mpi-env.sh"
export OMP_NUM_THREADS=1
cd "$work"
# The stepping speed here sets the run's length: the steps of 8 s of simulated time, past the
# pour, over the difference between the stepping times ("done: N steps in T s") of a run to
# t = 9 s and one to t = 1 s, so that start-up, the pour and the first output do not count.
probe() {
  "$mpirun" -np 2 "$binary" scene.toml "${settings[@]}" --quiet --output-dir "probe$1" \
    --set simulation.end_time="$1" | sed -n 's/^done: \([0-9]*\) steps in \([0-9.]*\) s.*/\1 \2/p'
}
short=$(probe 1.0)
long=$(probe 9.0)
end_time=$(echo "$short $long" |
  awk '{ rate = ($3 - $1) / ($4 - $2); t = int(150 * rate * 5e-5); print t < 10 ? 10 : t }')
echo "probe: steps, seconds to t = 1 s: $short; to t = 9 s: $long; the run goes to t = $end_time s"

failures=0
fail() {
  echo "FAILED: $*"
  failures=1
}
ids=$(OUT=out/chain GPUDEM=$binary BACKEND=host \
  SBATCH_ARGS="--job-name=chain --gres=none --ntasks-per-node=2 --cpus-per-task=1 --time=1" \
  bash "$source_dir/scripts/slurm/submit_chain.sh" 5 scene.toml "${settings[@]}" \
  --set simulation.end_time="$end_time")
read -r -a jobs <<< "$(echo $ids)"
((${#jobs[@]} == 5)) || fail "submit_chain.sh printed '$ids'"
for ((wait = 0; wait < 60; ++wait)); do
  [[ $(squeue -h -j "${jobs[0]}" -o %T 2> /dev/null) == RUNNING ]] && break
  sleep 1
done
if [[ $(squeue -h -j "${jobs[0]}" -o %T 2> /dev/null) != RUNNING ]]; then
  echo "FAILED: job ${jobs[0]} did not start within 60 s: $(squeue -h -j "${jobs[0]}" -o '%T %r')"
  exit 1
fi
for ((wait = 0; wait < 900; wait += 5)); do
  [[ -z $(squeue -h -j "$(IFS=,; echo "${jobs[*]}")" 2> /dev/null) ]] && break
  sleep 5
done
[[ -z $(squeue -h 2> /dev/null) ]] || fail "jobs still queued after 15 minutes: $(squeue)"
"$mpirun" -np 2 "$binary" scene.toml "${settings[@]}" --quiet --output-dir out/straight \
  --set simulation.end_time="$end_time" > straight.log 2>&1 || fail "the straight run failed"

outputs=("${jobs[@]/#/chain-}")
outputs=("${outputs[@]/%/.out}")
grep -q "DUE TO TIME LIMIT" "${outputs[0]}" ||
  fail "job ${jobs[0]} was not cut by its time limit: $(tail -n 5 "${outputs[0]}")"
grep -q "restart from out/chain/checkpoint.h5" "${outputs[1]}" ||
  fail "job ${jobs[1]} did not resume: $(tail -n 5 "${outputs[1]}")"
grep -q "run complete: out/chain/checkpoint.h5" "${outputs[4]}" ||
  fail "job ${jobs[4]} did not find the run complete: $(tail -n 5 "${outputs[4]}")"
for dataset in position_radius velocity_inv_mass angular_velocity force id; do
  h5diff out/chain/checkpoint.h5 out/straight/checkpoint.h5 "/$dataset" "/$dataset" > /dev/null ||
    fail "final $dataset differs from the straight run's"
done
cmp -s out/chain/timeseries.csv out/straight/timeseries.csv ||
  fail "the time series differs from the straight run's"
((failures == 0)) &&
  echo "Slurm: job ${jobs[0]} hit its time limit, the chain resumed it to the straight run's state"
exit $failures
