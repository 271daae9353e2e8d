# Start-up shares: particles and contact-history records sent from each rank's share to their
# owners (ShareRouting.hpp, RowShare.hpp), on 1, 2 and 4 ranks.
gpudem_add_test(test_share_routing
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/ShareRoutingTest.cpp
  LIBS gpudem_comm
  LABELS mpi
  TIMEOUT 60)
foreach(ranks 2 4)
  add_test(NAME test_share_routing_np${ranks}
    COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${ranks} ${MPIEXEC_PREFLAGS}
            $<TARGET_FILE:test_share_routing> ${MPIEXEC_POSTFLAGS})
  set_tests_properties(test_share_routing_np${ranks} PROPERTIES
    LABELS mpi
    TIMEOUT 120
    PROCESSORS ${ranks}
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
endforeach()
