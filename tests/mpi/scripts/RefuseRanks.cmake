# Runs gpudem-mpi on two ranks and checks: exit code 2, the one-rank message, no output.
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND ${MPIRUN} -np 2 ${BINARY} ${SCENE} --output-dir ${OUT}
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 2)
  message(FATAL_ERROR "expected exit code 2, got '${code}'\n${out}\n${err}")
endif()
string(FIND "${out}${err}" "runs on one MPI rank" at)
if(at EQUAL -1)
  message(FATAL_ERROR "message missing:\n${out}\n${err}")
endif()
if(EXISTS "${OUT}")
  message(FATAL_ERROR "output directory was created")
endif()
