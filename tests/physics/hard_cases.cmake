# The hard cases of inputs/hard/ (tests/scripts/check_hard_cases.py): a projectile refused ten
# times faster and stable at its speed; a plate at 5 m/s that no grain passes through; two beds
# that settle (radii 10:1, stiffness 100:1); stiff grains under a loaded piston for 10^6 steps;
# and a step past the stable limit that stops with its reason. Each on the host backend
# (hard_*) and on the CUDA backend (hard_cuda_*, skipped without a CUDA build or device).
foreach(backend host cuda)
  foreach(case projectile unstable tool piston settle:polydisperse_bed.toml
               settle:stiffness_contrast_bed.toml)
    string(REPLACE ":" ";" parts ${case})
    list(POP_FRONT parts kind)
    string(REGEX REPLACE "[:.]" "_" name ${case})
    if(backend STREQUAL "cuda")
      set(name cuda_${name})
    endif()
    add_test(NAME hard_${name}
      COMMAND /usr/bin/python3 ${CMAKE_CURRENT_LIST_DIR}/../scripts/check_hard_cases.py
              --backend ${backend} ${kind} ${PROJECT_SOURCE_DIR} $<TARGET_FILE:gpudem-mpi>
              ${CMAKE_CURRENT_BINARY_DIR}/hard_${name} ${parts})
    set_tests_properties(hard_${name} PROPERTIES LABELS physics TIMEOUT 600
      SKIP_RETURN_CODE 77 ENVIRONMENT "OMP_NUM_THREADS=1")
  endforeach()
endforeach()
