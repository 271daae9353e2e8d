# scripts/janssen_fit.py (the fit of scripts/janssen_column.sh) on synthetic columns of known
# saturation mass and wall friction, and its refusals of bad input.
add_test(NAME janssen_fit
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_janssen_fit.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/janssen_fit)
set_tests_properties(janssen_fit PROPERTIES LABELS unit TIMEOUT 60)
