gpudem_add_test(test_lanes SOURCES unit/LanesTest.cpp LIBS gpudem_sim LABELS unit)
# The objects built for x86-64-v4 and x86-64-v3 define nothing but their sweeps in lanes and
# the neighbour search's slot test in their vectors.
if(GPUDEM_HOST_LANES)
  add_test(NAME lanes_objects_hold_only_sweeps
    COMMAND ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_lanes_symbols.sh
            sweep_in_avx512_lanes slots_within_avx512
            $<TARGET_OBJECTS:gpudem_host_lanes_avx512>
    COMMAND_EXPAND_LISTS)
  add_test(NAME avx2_lanes_objects_hold_only_sweeps
    COMMAND ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_lanes_symbols.sh
            sweep_in_avx2_lanes slots_within_avx2
            $<TARGET_OBJECTS:gpudem_host_lanes_avx2>
    COMMAND_EXPAND_LISTS)
  set_tests_properties(lanes_objects_hold_only_sweeps avx2_lanes_objects_hold_only_sweeps
                       PROPERTIES LABELS unit TIMEOUT 60)
endif()
