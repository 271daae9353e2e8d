gpudem_add_test(test_lanes SOURCES unit/LanesTest.cpp LIBS gpudem_sim LABELS unit)
# The objects built for x86-64-v4 define nothing but the AVX-512 sweeps.
if(GPUDEM_HOST_LANES)
  add_test(NAME lanes_objects_hold_only_sweeps
    COMMAND ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_lanes_symbols.sh
            $<TARGET_OBJECTS:gpudem_host_lanes>
    COMMAND_EXPAND_LISTS)
  set_tests_properties(lanes_objects_hold_only_sweeps PROPERTIES LABELS unit TIMEOUT 60)
endif()
