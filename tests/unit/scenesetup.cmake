gpudem_add_test(test_scene_setup
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/SceneSetupTest.cpp
  LIBS gpudem_sim
  LABELS unit
  TIMEOUT 120)
add_dependencies(test_scene_setup gpudem-mpi)
# Particles a mesh overlaps where a new run starts, on one and on fake ranks.
gpudem_add_test(test_mesh_start_overlap
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/MeshStartOverlapTest.cpp
  LIBS gpudem_sim
  LABELS unit
  TIMEOUT 60)
# What JKR adhesion asks of the setup: pair values, the skin and the stable step.
gpudem_add_test(test_jkr_setup
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/JkrSetupTest.cpp
  LIBS gpudem_sim
  LABELS unit)
# [[bond]] tables and fixed materials: the keys, the refusals, the skin and the stable step.
gpudem_add_test(test_bond_scene
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/BondSceneTest.cpp
  LIBS gpudem_sim
  LABELS unit)
