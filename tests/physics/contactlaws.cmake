gpudem_add_test(test_normal_impact SOURCES physics/NormalImpactTest.cpp LIBS gpudem_sim LABELS physics)
gpudem_add_test(test_oblique_impact SOURCES physics/ObliqueImpactTest.cpp LIBS gpudem_sim LABELS physics)
gpudem_add_test(test_friction SOURCES physics/FrictionTest.cpp LIBS gpudem_sim LABELS physics)
gpudem_add_test(test_mesh_wall SOURCES physics/MeshWallTest.cpp LIBS gpudem_sim LABELS physics)
