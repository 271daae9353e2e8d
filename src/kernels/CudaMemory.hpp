#pragma once
/// Plain C++ declarations of the CUDA runtime calls the host side needs. Host headers include
/// this instead of cuda_runtime.h; the definitions live in CudaMemory.cu (CUDA builds only).
#include <cstddef>
#include <string>

namespace gpudem::cuda {

/// True when this binary was built with the CUDA backend.
bool compiled_in();
/// Number of visible CUDA devices (0 when none or when not compiled in).
int device_count();
/// Makes device `index` (in [0, device_count())) the current device of this process.
void select_device(int index);
/// Index of the current device.
int current_device();
/// Name and memory of the current device, for the start-up banner.
std::string device_description();

void* allocate(std::size_t bytes);
void release(void* ptr);
void copy_to_device(void* dst, const void* src, std::size_t bytes);
void copy_to_host(void* dst, const void* src, std::size_t bytes);
void copy_on_device(void* dst, const void* src, std::size_t bytes);

}  // namespace gpudem::cuda
