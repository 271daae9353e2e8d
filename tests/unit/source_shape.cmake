# The sources' shape (scripts/source_shape.py): no file in src/ over 500 lines, no function over
# 60; and the checker itself on synthetic trees.
add_test(NAME source_shape
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/source_shape.py ${PROJECT_SOURCE_DIR}/src)
add_test(NAME source_shape_checker
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_source_shape.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/source_shape)
set_tests_properties(source_shape source_shape_checker PROPERTIES LABELS unit TIMEOUT 60)
# The layers (scripts/layers.py): includes only downward, MPI only in src/comm, CUDA headers only
# in .cu/.cuh files; and the checker itself on synthetic trees.
add_test(NAME layers
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/layers.py ${PROJECT_SOURCE_DIR}/src)
add_test(NAME layers_checker
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_layers.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/layers)
set_tests_properties(layers layers_checker PROPERTIES LABELS unit TIMEOUT 60)
