# The tool-force plot (scripts/plot_draft.py) on a synthetic time series: draft, vertical and
# lateral force from the travel direction of the scene's motion or an axis, over the given steady
# window or the one of the tool's pass through the bed.
add_test(NAME plot_draft
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_plot_draft.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/plot_draft)
set_tests_properties(plot_draft PROPERTIES LABELS unit TIMEOUT 60)
