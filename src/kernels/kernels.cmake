# The step engine, instantiated per backend, normal law and precision from one template
# (StepEngineImpl.hpp via EngineFactory.hpp), one translation unit each; launch tuning.
add_library(gpudem_kernels STATIC
  kernels/LaunchTuning.cpp kernels/StepEngineHost.cpp
  kernels/StepEngineHostHookeDouble.cpp kernels/StepEngineHostHertzDouble.cpp
  kernels/StepEngineHostHookeMixed.cpp kernels/StepEngineHostHertzMixed.cpp)
target_link_libraries(gpudem_kernels PUBLIC gpudem_contact_model gpudem_mesh)
if(GPUDEM_HAVE_CUDA)
  target_sources(gpudem_kernels PRIVATE kernels/CudaMemory.cu kernels/StepEngineCuda.cu
    kernels/StepEngineCudaHookeDouble.cu kernels/StepEngineCudaHertzDouble.cu
    kernels/StepEngineCudaHookeMixed.cu kernels/StepEngineCudaHertzMixed.cu)
  set_target_properties(gpudem_kernels PROPERTIES CUDA_SEPARABLE_COMPILATION OFF)
  target_compile_options(gpudem_kernels PRIVATE $<$<COMPILE_LANGUAGE:CUDA>:--extended-lambda>)
  find_package(CUDAToolkit REQUIRED)
  target_link_libraries(gpudem_kernels PUBLIC CUDA::cudart)
else()
  target_sources(gpudem_kernels PRIVATE kernels/CudaMemoryStub.cpp)
endif()
