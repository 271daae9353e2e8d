gpudem_add_test(test_contact_law
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/ContactLawTest.cpp
  LIBS gpudem_engine
  LABELS unit)
# The build option GPUDEM_CONTACT_LAWS, configured in a scratch tree.
add_test(NAME contact_laws_option
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_contact_laws_option.sh ${PROJECT_SOURCE_DIR}
          ${CMAKE_CURRENT_BINARY_DIR}/contact_laws_option)
set_tests_properties(contact_laws_option PROPERTIES LABELS unit TIMEOUT 300)
gpudem_add_test(test_jkr_law
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/JkrLawTest.cpp
  LIBS gpudem_contact_model
  LABELS unit)
gpudem_add_test(test_parallel_bond
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/ParallelBondTest.cpp
  LIBS gpudem_contact_model
  LABELS unit)
