# The non-blocking exchange of contiguous buffers between ranks (DomainLink::start_exchange) and
# the collectives, with MPI waits that spin and that sleep, on 1, 2 and 4 ranks.
gpudem_add_test(test_domain_exchange
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/DomainExchangeTest.cpp
  LIBS gpudem_comm
  LABELS mpi
  TIMEOUT 60)
gpudem_add_test_on_ranks(test_domain_exchange RANKS 2 4 FILTER "*DomainExchange.*:DomainRefusal.*")
