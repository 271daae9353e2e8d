gpudem_add_test(test_mesh_scene SOURCES unit/MeshSceneTest.cpp LABELS unit TIMEOUT 120)
add_dependencies(test_mesh_scene gpudem-mpi)
