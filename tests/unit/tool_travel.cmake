# The steady window of a tool's pass through the bed (scripts/tool_travel.py, used by
# scripts/plot_draft.py and scripts/tillage_study.py) on synthetic motions along +x, −x and +y.
add_test(NAME tool_travel
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_tool_travel.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/tool_travel)
set_tests_properties(tool_travel PROPERTIES LABELS unit TIMEOUT 60)
