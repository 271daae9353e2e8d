gpudem_add_test(test_mesh_candidates
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/MeshCandidateListTest.cpp
  LIBS gpudem_engine gpudem_mesh
  LABELS unit)
