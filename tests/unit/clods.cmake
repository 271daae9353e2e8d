# scripts/clod_fragments.py (fragment sizes of bonded clods before and after a run) on a known
# bond graph, and its refusals.
add_test(NAME clod_fragments
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_clod_fragments.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/clod_fragments)
set_tests_properties(clod_fragments PROPERTIES LABELS unit TIMEOUT 60)
