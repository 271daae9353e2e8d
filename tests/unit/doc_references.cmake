# What the README, docs/ and the shipped scenes name exists (scripts/doc_references.py): links and
# their headings, the project's paths, the scene tables' sections; and the checker itself on
# synthetic trees.
add_test(NAME doc_references
  COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/doc_references.py ${PROJECT_SOURCE_DIR})
add_test(NAME doc_references_checker
  COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_doc_references.py
          ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/doc_references)
set_tests_properties(doc_references doc_references_checker PROPERTIES LABELS unit TIMEOUT 60)
