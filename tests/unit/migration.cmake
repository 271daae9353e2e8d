# Migration between ranks (ParticleMigration.hpp) on fake ranks in one process
# (support/FakeRanks.hpp).
gpudem_add_test(test_migration
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/MigrationTest.cpp
  LIBS gpudem_engine
  LABELS unit
  TIMEOUT 60)
# The collectives every layer shares (core/RankGroup.hpp), on fake ranks.
gpudem_add_test(test_rank_group
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/RankGroupTest.cpp
  LIBS gpudem_engine
  LABELS unit
  TIMEOUT 60)
# Ghost exchange (GhostExchange.hpp) on fake ranks with a real decomposition.
gpudem_add_test(test_ghost_exchange
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/GhostExchangeTest.cpp
  LIBS gpudem_decomposition
  LABELS unit
  TIMEOUT 60)
# The particle field table (core/ParticleFields.hpp): wire rows, the host store and the
# engine's per-field arrays on the host backend.
gpudem_add_test(test_particle_fields
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/ParticleFieldsTest.cpp
  LIBS gpudem_engine
  LABELS unit
  TIMEOUT 60)
