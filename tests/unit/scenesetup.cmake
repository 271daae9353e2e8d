gpudem_add_test(test_scene_setup
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/SceneSetupTest.cpp
  LIBS gpudem_sim
  LABELS unit
  TIMEOUT 120)
add_dependencies(test_scene_setup gpudem-mpi)
