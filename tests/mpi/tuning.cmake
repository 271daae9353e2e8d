# Launch tuning agrees across ranks: the same injected-timing test alone (one rank) and through
# mpiexec at 2 and 4 ranks (Open MPI needs the variables below as root and past the core count).
gpudem_add_test(test_launch_tuning_agreement
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/LaunchTuningAgreementTest.cpp
  LIBS gpudem_comm gpudem_kernels
  LABELS mpi
  TIMEOUT 60)
foreach(ranks 2 4)
  add_test(NAME test_launch_tuning_agreement_np${ranks}
    COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${ranks} ${MPIEXEC_PREFLAGS}
            $<TARGET_FILE:test_launch_tuning_agreement> ${MPIEXEC_POSTFLAGS})
  set_tests_properties(test_launch_tuning_agreement_np${ranks} PROPERTIES
    LABELS mpi
    TIMEOUT 120
    PROCESSORS ${ranks}
    ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
endforeach()
