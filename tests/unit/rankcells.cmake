# The device side of a rebuild on several ranks: chosen CSR rows read out and appended, the
# particles near another rank's cells, the leaving particles' destinations (RankCells).
gpudem_add_test(test_rank_cells
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/RankCellsTest.cpp
  LIBS gpudem_engine gpudem_decomposition
  LABELS unit
  TIMEOUT 60)
if(GPUDEM_HAVE_CUDA)
  gpudem_add_test(test_rank_cells_cuda
    SOURCES ${CMAKE_CURRENT_LIST_DIR}/RankCellsCudaTest.cu
    LIBS gpudem_engine gpudem_decomposition
    LABELS unit
    TIMEOUT 60)
endif()
