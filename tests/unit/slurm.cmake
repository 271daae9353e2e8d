# scripts/slurm/ (the batch template and the job chain) with stand-ins for srun and sbatch: a
# run cut short and resumed by a second job on 2 ranks, and the dependencies of a chain.
find_program(GPUDEM_SLURM_TEST_MPIRUN NAMES mpirun mpiexec REQUIRED)
add_test(NAME slurm_scripts
  COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_slurm_scripts.sh ${PROJECT_SOURCE_DIR}
          $<TARGET_FILE:gpudem-mpi> ${GPUDEM_SLURM_TEST_MPIRUN}
          ${CMAKE_CURRENT_BINARY_DIR}/slurm_scripts)
set_tests_properties(slurm_scripts PROPERTIES LABELS unit TIMEOUT 120 PROCESSORS 2)

# The same scripts under Debian's Slurm started for real on this machine (skipped, saying why,
# where it is missing or does not start): a job cut by its time limit, the chain resuming it to
# the state of a straight run. About five minutes, both cores.
add_test(NAME slurm_real
  COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_slurm_real.sh ${PROJECT_SOURCE_DIR}
          $<TARGET_FILE:gpudem-mpi> ${GPUDEM_SLURM_TEST_MPIRUN}
          ${CMAKE_CURRENT_BINARY_DIR}/slurm_real)
set_tests_properties(slurm_real PROPERTIES LABELS unit TIMEOUT 1200 PROCESSORS 2
                     SKIP_RETURN_CODE 77)
