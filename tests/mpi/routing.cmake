# Start-up shares: particles and contact-history records sent from each rank's share to their
# owners (ShareRouting.hpp, RowShare.hpp), on 1, 2 and 4 ranks.
gpudem_add_test(test_share_routing
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/ShareRoutingTest.cpp
  LIBS gpudem_comm
  LABELS mpi
  TIMEOUT 60)
gpudem_add_test_on_ranks(test_share_routing RANKS 2 4)

# Tiled insertion by parts, one per rank, passing boundary spheres after each phase
# (TiledParts.hpp), on 1, 2, 3 and 4 ranks.
gpudem_add_test(test_tiled_parts
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/TiledPartsTest.cpp
  LIBS gpudem_comm
  LABELS mpi
  TIMEOUT 120)
gpudem_add_test_on_ranks(test_tiled_parts RANKS 2 3 4)

# A new run's particles made by parts, every kind of source one after another (StartParts.hpp),
# on 1, 2, 3 and 4 ranks.
gpudem_add_test(test_start_parts
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/StartPartsTest.cpp
  LIBS gpudem_comm
  LABELS mpi
  TIMEOUT 120)
gpudem_add_test_on_ranks(test_start_parts RANKS 2 3 4)
