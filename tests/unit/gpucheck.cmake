# scripts/gpu_check.sh (run on GPU machines) against a stub bundle: its time budget, test order
# and verdicts (tests/scripts/gpu_check_budget.sh).
add_test(NAME gpu_check_budget
  COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/../scripts/gpu_check_budget.sh ${PROJECT_SOURCE_DIR})
set_tests_properties(gpu_check_budget PROPERTIES LABELS unit TIMEOUT 60)
