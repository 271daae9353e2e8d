# scripts/scaling_model.py: its halo against the closed form, against every measured point,
# and its predictions' bounds.
add_test(NAME scaling_model
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_scaling_model.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/scaling_model)
set_tests_properties(scaling_model PROPERTIES LABELS unit TIMEOUT 60)
