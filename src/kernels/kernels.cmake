# The step engine, instantiated per backend, normal law and precision policy from one template
# (StepEngineImpl.hpp via EngineFactory.hpp), one generated translation unit each so that they
# compile in parallel; launch tuning.
add_library(gpudem_kernels ${GPUDEM_LIBRARY_TYPE} kernels/LaunchTuning.cpp kernels/StepEngineHost.cpp)
target_link_libraries(gpudem_kernels PUBLIC gpudem_contact_model gpudem_mesh)

# Adds to gpudem_kernels one translation unit per normal law and precision policy of a backend:
# BACKEND (Host, Cuda), its factory prefix, execution space, parallel_for header and extension.
function(gpudem_add_engine_instances backend factory space parallel_for_header extension)
  foreach(LAW Hooke Hertz)
    string(TOLOWER ${LAW} LAW_NAME)
    foreach(POLICY Double Mixed Float)
      string(TOLOWER ${POLICY} POLICY_NAME)
      set(BACKEND ${backend})
      set(FACTORY ${factory})
      set(SPACE ${space})
      set(PARALLEL_FOR_HEADER ${parallel_for_header})
      set(file ${CMAKE_CURRENT_BINARY_DIR}/generated/StepEngine${backend}${LAW}${POLICY}.${extension})
      configure_file(${CMAKE_CURRENT_SOURCE_DIR}/kernels/StepEngineInstance.in ${file} @ONLY)
      target_sources(gpudem_kernels PRIVATE ${file})
    endforeach()
  endforeach()
endfunction()

gpudem_add_engine_instances(Host host HostSpace kernels/ParallelFor.hpp cpp)
if(GPUDEM_HAVE_CUDA)
  target_sources(gpudem_kernels PRIVATE kernels/CudaMemory.cu kernels/StepEngineCuda.cu)
  gpudem_add_engine_instances(Cuda cuda CudaSpace kernels/ParallelForCuda.cuh cu)
  set_target_properties(gpudem_kernels PROPERTIES CUDA_SEPARABLE_COMPILATION OFF)
  target_compile_options(gpudem_kernels PRIVATE $<$<COMPILE_LANGUAGE:CUDA>:--extended-lambda>)
  find_package(CUDAToolkit REQUIRED)
  target_link_libraries(gpudem_kernels PUBLIC CUDA::cudart)
else()
  target_sources(gpudem_kernels PRIVATE kernels/CudaMemoryStub.cpp)
endif()
