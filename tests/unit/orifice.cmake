# scripts/make_orifice_stl.py (the silo floors of scripts/silo_beverloo.sh): coverage, hole
# area and orientation of the plates it writes, and the shipped inputs/silo/orifice.stl.
add_test(NAME orifice_stl
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_orifice_stl.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/orifice_stl)
set_tests_properties(orifice_stl PROPERTIES LABELS unit TIMEOUT 60)
