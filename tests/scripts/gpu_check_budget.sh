#!/usr/bin/env bash
# scripts/gpu_check.sh run here against a stub bundle (no GPU needed): under a 12 s budget, a
# test that passes, one that exits with its skip code, one that fails, one the budget cuts and
# one it never reaches are each reported as such; FIRST starts its test first; a part the
# budget leaves no time for is listed as not reached; an unknown part is refused with exit 2
# before the bundle is unpacked.
# Usage: gpu_check_budget.sh SOURCE_DIR
set -euo pipefail
source_dir=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
repo=$tmp/repo
mkdir -p "$repo/scripts" "$repo/gpu-bundle" "$tmp/stub/gpudem-gpu/bin" "$tmp/unpacked"
cp "$source_dir/scripts/gpu_check.sh" "$repo/scripts/"
echo ': the stub runtime sets nothing' > "$tmp/stub/gpudem-gpu/env.sh"
tar -C "$tmp/stub" -cJf "$repo/gpu-bundle/gpudem-gpu.tar.xz" gpudem-gpu
echo "stub bundle" > "$repo/gpu-bundle/commit"
cat > "$repo/gpu-bundle/tests.sh" <<'TESTS'
run_test t_pass 100 77 -- true
run_test t_skip 100 77 -- bash -c "exit 77"
run_test t_fail 100 77 -- false
run_test t_long 100 77 -- sleep 60
run_test t_late 100 77 -- true
run_test t_first 100 77 -- true
TESTS
check() {
  env -i PATH="$PATH" HOME="$tmp" OUT="$tmp/out" WORK="$tmp/work" BUNDLE="$tmp/unpacked/gpudem-gpu" \
    BUDGET=12 FIRST=t_first TESTS_AT_ONCE=1 bash "$repo/scripts/gpu_check.sh" "$@"
}
failures=0
expect() {  # expect TEXT FILE: FILE holds the line TEXT
  if ! grep -qxF -- "$1" "$2"; then echo "missing in $(basename "$2"): $1"; failures=1; fi
}

status=0
check tests bogus > "$tmp/refused.txt" 2>&1 || status=$?
[ "$status" -eq 2 ] || { echo "an unknown part exited $status, not 2"; failures=1; }
[ ! -e "$tmp/unpacked/gpudem-gpu" ] || { echo "the bundle was unpacked for a refused call"; failures=1; }

check tests sanitizer > "$tmp/summary.txt" 2>&1
results=$tmp/work/logs/tests/results
[ "$(head -1 "$results")" = "passed t_first" ] || { echo "t_first did not run first"; failures=1; }
for line in "passed t_pass" "skipped t_skip" "FAILED t_fail (exit 1)" \
            "cut t_long (the budget ran out)" "not reached t_late"; do
  expect "$line" "$results"
done
expect "tests: 2 passed, 1 skipped, 1 failed, 2 cut or not reached by the budget; 0 GoogleTest cases skipped inside them" "$tmp/out/summary.txt"
expect "sanitizer: not reached (budget)" "$tmp/out/summary.txt"
[ -s "$tmp/out/logs.tar.gz" ] || { echo "no logs.tar.gz under OUT"; failures=1; }
if [ "$failures" -ne 0 ]; then cat "$tmp/summary.txt"; exit 1; fi
echo "gpu_check.sh: budget, order and verdicts as expected"
