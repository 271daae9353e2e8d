# scripts/repose_angle.py (the heap angle of scripts/heap_vs_liggghts.sh) on synthetic heaps of
# known flank angles, from a snapshot and from a LIGGGHTS dump, and its refusals.
add_test(NAME repose_angle
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_repose_angle.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/repose_angle)
set_tests_properties(repose_angle PROPERTIES LABELS unit TIMEOUT 60)

# scripts/make_cylinder_stl.py (the lifting cylinder of inputs/heap/): its tubes and the shipped
# inputs/heap/cylinder.stl.
add_test(NAME cylinder_stl
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_cylinder_stl.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/cylinder_stl)
set_tests_properties(cylinder_stl PROPERTIES LABELS unit TIMEOUT 60)
