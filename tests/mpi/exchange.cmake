# The non-blocking exchange of contiguous buffers between ranks (DomainLink::start_exchange)
# on 1, 2 and 4 ranks. Open MPI runs as root and past the core count only when told so; these
# variables do that and other MPIs ignore them.
gpudem_add_test(test_domain_exchange
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/DomainExchangeTest.cpp
  LIBS gpudem_comm
  LABELS mpi
  TIMEOUT 60)
foreach(ranks 2 4)
  add_test(NAME test_domain_exchange_np${ranks}
    COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${ranks} ${MPIEXEC_PREFLAGS}
            $<TARGET_FILE:test_domain_exchange> ${MPIEXEC_POSTFLAGS}
            --gtest_filter=DomainExchange.*)
  set_tests_properties(test_domain_exchange_np${ranks} PROPERTIES
    LABELS mpi
    TIMEOUT 120
    PROCESSORS ${ranks}
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
endforeach()
