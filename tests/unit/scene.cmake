gpudem_add_test(test_scene_loader
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/SceneLoaderTest.cpp
  LIBS gpudem_scene
  LABELS unit
  TIMEOUT 60)
