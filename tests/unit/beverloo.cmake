# scripts/beverloo_fit.py (the fit of scripts/silo_beverloo.sh) on synthetic discharges of known
# C and k from a lattice bed of known solid fraction: its fit, its verdicts and its refusals.
add_test(NAME beverloo_fit
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_beverloo_fit.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/beverloo_fit)
set_tests_properties(beverloo_fit PROPERTIES LABELS unit TIMEOUT 60)
