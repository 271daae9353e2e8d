# Migration between ranks (ParticleMigration.hpp) on fake ranks in one process
# (support/FakeRanks.hpp), and the fake ranks' collectives.
gpudem_add_test(test_migration
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/MigrationTest.cpp
  LIBS gpudem_kernels
  LABELS unit
  TIMEOUT 60)
