#!/usr/bin/env bash
# scripts/slurm/ without Slurm: stand-ins for srun (mpirun on SLURM_NTASKS ranks, recording
# its arguments) and sbatch (recording its arguments, printing job ids 101, 102, ...).
# gpudem.sbatch run as two jobs of one run on 2 ranks, the first cut short at half the end
# time: the first starts the scene, the second resumes it from the checkpoint to the end, a
# third finds it complete; each launches srun with the scene, --resume, the output folder, the
# backend and the options given, and one OpenMP thread per core it was given. submit_chain.sh
# submits three jobs, each after the one before, and refuses a job count that is not a
# positive integer.
# Usage: check_slurm_scripts.sh SOURCE_DIR GPUDEM_BINARY MPIRUN WORK_DIR
set -euo pipefail
source_dir=$1 binary=$2 mpirun=$3 work=$4
rm -rf "$work"
mkdir -p "$work/bin"
failures=0
fail() { echo "FAILED: $*"; failures=1; }

cat > "$work/bin/srun" <<STUB
#!/usr/bin/env bash
echo "srun \$* OMP_NUM_THREADS=\$OMP_NUM_THREADS" >> "$work/srun.log"
while [[ \$1 == --* ]]; do shift; done
exec "$mpirun" --allow-run-as-root --oversubscribe -np "\$SLURM_NTASKS" "\$@"
STUB
cat > "$work/bin/sbatch" <<STUB
#!/usr/bin/env bash
echo "sbatch \$*" >> "$work/sbatch.log"
n=\$(wc -l < "$work/sbatch.log")
echo "\$((100 + n));cluster"
STUB
chmod +x "$work/bin/srun" "$work/bin/sbatch"

cp "$source_dir/tests/scripts/slurm_scene.toml" "$work/scene.toml"

for v in $(env | grep -Eo '^(OMPI|PMIX|OPAL)_[A-Za-z0-9_]*'); do unset "$v"; done
job() {  # one batch job of the run: gpudem.sbatch as sbatch would start it
  (cd "$work" && PATH="$work/bin:$PATH" SLURM_JOB_ID=$1 SLURM_JOB_NAME=chain SLURM_NTASKS=2 \
    SLURM_CPUS_PER_TASK=1 GPUDEM="$binary" BACKEND=host \
    bash "$source_dir/scripts/slurm/gpudem.sbatch" scene.toml "${@:2}")
}
job 1 --quiet --set simulation.end_time=0.05 > "$work/job1.out" 2>&1 || fail "job 1 exited $?"
job 2 > "$work/job2.out" 2>&1 || fail "job 2 exited $?"
job 3 > "$work/job3.out" 2>&1 || fail "job 3 exited $?"
grep -q "restart from out/chain/checkpoint.h5 at t = 0.05 s" "$work/job2.out" ||
  fail "job 2 did not resume from the checkpoint: $(cat "$work/job2.out")"
grep -q "run complete: out/chain/checkpoint.h5 is at t = 0.1 s, end_time = 0.1 s" \
  "$work/job3.out" || fail "job 3 did not find the run complete: $(cat "$work/job3.out")"
last=$(tail -n 1 "$work/out/chain/timeseries.csv" | cut -d, -f1)
[[ $last == 0.1 ]] || fail "the time series ends at t = $last, not 0.1"
expected="srun --cpus-per-task=1 --cpu-bind=cores $binary scene.toml --resume --output-dir out/chain --backend host"
expected+=" --quiet --set simulation.end_time=0.05 OMP_NUM_THREADS=1"
[[ $(head -n 1 "$work/srun.log") == "$expected" ]] ||
  fail "job 1 ran '$(head -n 1 "$work/srun.log")', expected '$expected'"
[[ $(wc -l < "$work/srun.log") -eq 3 ]] || fail "expected three srun calls"

chain="$source_dir/scripts/slurm/submit_chain.sh"
ids=$(PATH="$work/bin:$PATH" SBATCH_ARGS="--nodes=2 --time=1:00:00" bash "$chain" 3 bed.toml \
  --set simulation.end_time=2)
[[ $(echo $ids) == "101 102 103" ]] || fail "submit_chain.sh printed '$ids'"
template="$source_dir/scripts/slurm/gpudem.sbatch"
template=$(cd "$(dirname "$template")" && pwd)/gpudem.sbatch
mapfile -t calls < "$work/sbatch.log"
tail_args="$template bed.toml --set simulation.end_time=2"
[[ ${calls[0]} == "sbatch --parsable --nodes=2 --time=1:00:00 $tail_args" ]] ||
  fail "first submission: ${calls[0]}"
[[ ${calls[1]} == "sbatch --parsable --nodes=2 --time=1:00:00 --dependency=afterany:101 $tail_args" ]] ||
  fail "second submission: ${calls[1]}"
[[ ${calls[2]} == "sbatch --parsable --nodes=2 --time=1:00:00 --dependency=afterany:102 $tail_args" ]] ||
  fail "third submission: ${calls[2]}"
for bad in 0 x -1; do
  status=0
  PATH="$work/bin:$PATH" bash "$chain" "$bad" bed.toml > /dev/null 2>&1 || status=$?
  [[ $status -eq 2 ]] || fail "JOBS = $bad: exit $status, expected 2"
done
[[ $(wc -l < "$work/sbatch.log") -eq 3 ]] || fail "a refused chain submitted jobs"
[[ $failures -eq 0 ]] && echo "slurm scripts: a resumed two-job run completes; chains depend in order"
exit $failures
