# Soil beds: a [preparation] run settles, trims and saves a bed; a scene starts from it with
# [[insert]] bed = "...".
gpudem_add_test(test_bed_preparation
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/BedPreparationTest.cpp
  LIBS gpudem_comm
  LABELS unit
  TIMEOUT 120)
add_dependencies(test_bed_preparation gpudem-mpi)
set_tests_properties(test_bed_preparation PROPERTIES PROCESSORS 2)  # one case runs on 2 ranks
