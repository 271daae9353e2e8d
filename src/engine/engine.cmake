# The step engine per backend: the particle system once per precision policy
# (ParticleSystemInstance.in) and the force computes once per normal law and law scalar, double
# or float (ForceComputeInstance.in, EngineFactory.hpp), one generated translation unit each so
# that they compile in parallel; launch tuning.
add_library(gpudem_engine ${GPUDEM_LIBRARY_TYPE} engine/CoarseGrid.cpp engine/ExactSum.cpp engine/LaunchTuning.cpp
            engine/StepEngineHost.cpp)
target_link_libraries(gpudem_engine PUBLIC gpudem_contact_model gpudem_mesh)

# Adds to gpudem_engine the generated translation units of a backend: BACKEND (Host, Cuda),
# its execution space, parallel_for header and source extension.
function(gpudem_add_engine_instances backend space parallel_for_header extension)
  set(BACKEND ${backend})
  set(SPACE ${space})
  set(PARALLEL_FOR_HEADER ${parallel_for_header})
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/generated)
  foreach(POLICY Double Mixed Float)
    string(TOLOWER ${POLICY} POLICY_NAME)
    set(file ${dir}/ParticleSystem${backend}${POLICY}.${extension})
    configure_file(${CMAKE_CURRENT_SOURCE_DIR}/engine/ParticleSystemInstance.in ${file} @ONLY)
    target_sources(gpudem_engine PRIVATE ${file})
  endforeach()
  foreach(SCALAR double float)
    foreach(LAW Hooke Hertz)
      string(TOLOWER ${LAW} LAW_NAME)
      set(file ${dir}/ForceCompute${backend}${LAW}_${SCALAR}.${extension})
      configure_file(${CMAKE_CURRENT_SOURCE_DIR}/engine/ForceComputeInstance.in ${file} @ONLY)
      target_sources(gpudem_engine PRIVATE ${file})
    endforeach()
  endforeach()
endfunction()

gpudem_add_engine_instances(Host HostSpace engine/ParallelFor.hpp cpp)

# The host's pair sweeps in lanes (PairLanesInstance.in), one unit per normal law and law scalar
# and vector width, each instantiating the sweep of every damping, tangential, rolling and
# cohesion choice (enum values; the uncompiled ones are empty): eight lanes built for x86-64-v4
# (AVX-512) in gpudem_host_lanes_avx512 and four built for x86-64-v3 (AVX2) in
# gpudem_host_lanes_avx2, each with the neighbour search's test of a run of slots in those
# vectors (NeighborSlotsAvx512.cpp, NeighborSlotsAvx2.cpp). Only these units are built for
# those targets.
if(GPUDEM_HOST_LANES)
  set(LANES_INSTANCES "")
  foreach(D RANGE 2)
    foreach(T RANGE 2)
      foreach(R RANGE 2)
        foreach(C RANGE 2)
          string(APPEND LANES_INSTANCES "GPUDEM_SWEEP_IN_LANES(${D}, ${T}, ${R}, ${C})\n")
        endforeach()
      endforeach()
    endforeach()
  endforeach()
  foreach(VECTORS avx512 avx2)
    if(VECTORS STREQUAL "avx512")
      set(WIDTH 8)
      set(LANES_TARGET x86-64-v4)
    else()
      set(WIDTH 4)
      set(LANES_TARGET x86-64-v3)
    endif()
    set(SWEEP sweep_in_${VECTORS}_lanes)
    set(lib gpudem_host_lanes_${VECTORS})
    add_library(${lib} OBJECT)
    foreach(SCALAR double float)
      foreach(LAW Hooke Hertz)
        string(TOLOWER ${LAW} LAW_NAME)
        set(file ${CMAKE_CURRENT_BINARY_DIR}/generated/PairLanes${LAW}_${SCALAR}_${VECTORS}.cpp)
        configure_file(${CMAKE_CURRENT_SOURCE_DIR}/engine/PairLanesInstance.in ${file} @ONLY)
        target_sources(${lib} PRIVATE ${file})
      endforeach()
    endforeach()
    target_link_libraries(${lib} PRIVATE gpudem_contact_model gpudem_mesh)
    target_compile_options(${lib} PRIVATE -march=${LANES_TARGET})
    if(GPUDEM_LIBRARY_TYPE STREQUAL "SHARED")
      set_target_properties(${lib} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    endif()
    target_sources(gpudem_engine PRIVATE $<TARGET_OBJECTS:${lib}>)
  endforeach()
  target_sources(gpudem_host_lanes_avx512
                 PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/engine/NeighborSlotsAvx512.cpp)
  target_sources(gpudem_host_lanes_avx2
                 PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/engine/NeighborSlotsAvx2.cpp)
endif()
if(GPUDEM_HAVE_CUDA)
  target_sources(gpudem_engine PRIVATE engine/CudaMemory.cu engine/CudaPrimitives.cu
                                       engine/StepEngineCuda.cu)
  gpudem_add_engine_instances(Cuda CudaSpace engine/ParallelForCuda.cuh cu)
  set_target_properties(gpudem_engine PROPERTIES CUDA_SEPARABLE_COMPILATION OFF)
  target_compile_options(gpudem_engine PRIVATE $<$<COMPILE_LANGUAGE:CUDA>:--extended-lambda>)
  find_package(CUDAToolkit REQUIRED)
  target_link_libraries(gpudem_engine PUBLIC CUDA::cudart)
else()
  target_sources(gpudem_engine PRIVATE engine/CudaMemoryStub.cpp)
endif()
