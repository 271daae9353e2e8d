/// CudaMemory.hpp for builds without the CUDA backend: no device, and any allocation is a
/// programming error (the backend selection refuses "cuda" before it gets here).
#include <stdexcept>

#include "engine/CudaMemory.hpp"

namespace gpudem::cuda {

namespace {
[[noreturn]] void unavailable() {
  throw std::logic_error("this gpudem-mpi was built without the CUDA backend");
}
}  // namespace

bool compiled_in() { return false; }
int device_count() { return 0; }
void select_device(int) { unavailable(); }
int current_device() { unavailable(); }
std::string device_description() { return "none"; }
std::size_t free_device_memory() { unavailable(); }
void* allocate(std::size_t) { unavailable(); }
void release(void* ptr) {
  if (ptr) unavailable();
}
void copy_to_device(void*, const void*, std::size_t) { unavailable(); }
void copy_to_host(void*, const void*, std::size_t) { unavailable(); }
void copy_on_device(void*, const void*, std::size_t) { unavailable(); }
void* allocate_pinned(std::size_t) { unavailable(); }
void release_pinned(void* ptr) {
  if (ptr) unavailable();
}
Stream create_stream() { unavailable(); }
void destroy_stream(Stream stream) {
  if (stream) unavailable();
}
void copy_to_host_async(void*, const void*, std::size_t, Stream) { unavailable(); }
void copy_to_device_async(void*, const void*, std::size_t, Stream) { unavailable(); }
void synchronize(Stream) { unavailable(); }
void synchronize_device() { unavailable(); }

}  // namespace gpudem::cuda
