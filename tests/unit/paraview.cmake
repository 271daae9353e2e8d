# When ParaView's Python module is installed (Debian: python3-paraview, not required), the
# snapshot fixture is also opened with ParaView's own XDMF readers.
execute_process(COMMAND /usr/bin/python3 -c "import paraview.simple"
                RESULT_VARIABLE GPUDEM_NO_PARAVIEW OUTPUT_QUIET ERROR_QUIET)
if(GPUDEM_NO_PARAVIEW EQUAL 0)
  add_test(NAME paraview_opens_snapshots
    COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/paraview_open.py
            ${CMAKE_CURRENT_BINARY_DIR}/snapshot_fixture)
  set_tests_properties(paraview_opens_snapshots PROPERTIES
    FIXTURES_REQUIRED snapshot_fixture LABELS unit TIMEOUT 120)
else()
  message(STATUS "python3-paraview not found: the ParaView reader test is not registered")
endif()
