#!/usr/bin/env bash
# Runs the physics tests and prints the measured quantities they record, for docs/validation.md.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh > /dev/null
tests=(test_dynamics test_settling test_contact_history test_normal_impact test_oblique_impact
       test_friction test_janssen)
cmake --build build --target "${tests[@]}" -j "$(nproc)" > /dev/null
out=$(mktemp -d)
for t in "${tests[@]}"; do
  OMP_NUM_THREADS=${OMP_NUM_THREADS:-2} "build/tests/$t" --gtest_filter='*/host' \
    --gtest_output="xml:$out/$t.xml" > /dev/null
done
/usr/bin/python3 - "$out" <<'PY'
import glob, sys, xml.etree.ElementTree as ET
for path in sorted(glob.glob(sys.argv[1] + "/*.xml")):
    for case in ET.parse(path).iter("testcase"):
        props = {p.get("name"): p.get("value") for p in case.iter("property")}
        if props:
            print(f"{case.get('classname')}.{case.get('name')}: " +
                  ", ".join(f"{k} = {v}" for k, v in props.items()))
PY
rm -rf "$out"
