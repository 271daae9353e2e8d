#pragma once
/// Plain C++ declarations of the CUDA runtime calls the host side needs. Host headers include
/// this instead of cuda_runtime.h; the definitions live in CudaMemory.cu (CUDA builds only).
#include <cstddef>
#include <string>

struct CUstream_st;  // the CUDA runtime's stream object, opaque here

namespace gpudem::cuda {

/// A CUDA stream (the runtime's cudaStream_t).
using Stream = CUstream_st*;

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
/// Bytes of the current device's memory not yet allocated.
std::size_t free_device_memory();

void* allocate(std::size_t bytes);
void release(void* ptr);
void copy_to_device(void* dst, const void* src, std::size_t bytes);
void copy_to_host(void* dst, const void* src, std::size_t bytes);
void copy_on_device(void* dst, const void* src, std::size_t bytes);

/// Page-locked host memory, which asynchronous copies need.
void* allocate_pinned(std::size_t bytes);
void release_pinned(void* ptr);
/// A stream that waits for the work launched before it on the default stream, and that the
/// default stream's later work waits for (a blocking stream).
Stream create_stream();
void destroy_stream(Stream stream);
/// Copies queued on `stream`; the host side must be pinned memory.
void copy_to_host_async(void* dst, const void* src, std::size_t bytes, Stream stream);
void copy_to_device_async(void* dst, const void* src, std::size_t bytes, Stream stream);
/// Waits until the work queued on `stream` has finished.
void synchronize(Stream stream);
/// Waits until all work on the current device has finished.
void synchronize_device();

}  // namespace gpudem::cuda
