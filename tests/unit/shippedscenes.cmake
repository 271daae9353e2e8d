# Every scene shipped in inputs/ that does not start from the bed an earlier stage writes passes
# `gpudem-mpi --check` (the scene, its meshes, CSV files and sources read and checked, the
# particles created, nothing run; exit 0 only for a valid scene), so that the examples keep up
# with the input format. Calibration specs (a [calibration] table) are not scenes:
# calibration_specs.cmake checks them.
file(GLOB_RECURSE GPUDEM_SHIPPED_SCENES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/inputs/*.toml)
foreach(scene ${GPUDEM_SHIPPED_SCENES})
  file(STRINGS ${scene} bed_source REGEX "^bed *=")
  file(STRINGS ${scene} calibration_table REGEX "^\\[calibration\\]")
  if(bed_source OR calibration_table)
    continue()
  endif()
  file(RELATIVE_PATH name ${PROJECT_SOURCE_DIR}/inputs ${scene})
  string(REGEX REPLACE "[/.]" "_" name ${name})
  add_test(NAME shipped_scene_${name}
    COMMAND $<TARGET_FILE:gpudem-mpi> ${scene} --check --backend host)
  set_tests_properties(shipped_scene_${name} PROPERTIES LABELS unit TIMEOUT 300
    ENVIRONMENT "OMP_NUM_THREADS=1;OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1")
endforeach()
