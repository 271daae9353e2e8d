# Every calibration spec shipped in inputs/ (a TOML file with a [calibration] table; the scene
# check of shippedscenes.cmake skips them) passes scripts/calibrate.py --check: the spec read and
# checked, and gpudem-mpi --check on its scenes with every parameter at its bounds; nothing run.
file(GLOB_RECURSE GPUDEM_CALIBRATION_SPECS CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/inputs/*.toml)
foreach(spec ${GPUDEM_CALIBRATION_SPECS})
  file(STRINGS ${spec} calibration_table REGEX "^\\[calibration\\]")
  if(NOT calibration_table)
    continue()
  endif()
  file(RELATIVE_PATH name ${PROJECT_SOURCE_DIR}/inputs ${spec})
  string(REGEX REPLACE "[/.]" "_" name ${name})
  add_test(NAME calibration_spec_${name}
    COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/scripts/calibrate.py ${spec} --check
            --solver $<TARGET_FILE:gpudem-mpi>)
  set_tests_properties(calibration_spec_${name} PROPERTIES LABELS unit TIMEOUT 120
    ENVIRONMENT "OMP_NUM_THREADS=1")
endforeach()
