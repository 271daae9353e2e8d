# scripts/soil_disturbance.py on a synthetic pass of known furrow, ridge and throw (a lattice bed
# whose furrow is thrown onto a ridge beside it), along +x and mirrored along -x, and its refusals.
add_test(NAME soil_disturbance
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_soil_disturbance.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/soil_disturbance)
set_tests_properties(soil_disturbance PROPERTIES LABELS unit TIMEOUT 60)
