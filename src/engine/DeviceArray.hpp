#pragma once
/// A typed buffer in one memory space. Copies between spaces are explicit calls
/// (`upload`, `download`); nothing syncs behind the caller's back (docs/architecture.md, "One
/// source, two backends", rule 7).
#include <cstddef>
#include <utility>
#include <vector>

#include "engine/CudaMemory.hpp"
#include "engine/ExecutionSpace.hpp"
#include "engine/HostAllocator.hpp"

namespace gpudem {

template <class T, class Space>
class DeviceArray;

/// Host buffer: a std::vector on HostAllocator (huge pages from 2 MiB on).
template <class T>
class DeviceArray<T, HostSpace> {
 public:
  DeviceArray() = default;
  explicit DeviceArray(std::size_t n) : data_(n) {}
  T* data() { return data_.data(); }
  const T* data() const { return data_.data(); }
  std::size_t size() const { return data_.size(); }
  /// Resizes keeping the first min(old, new) elements.
  void resize(std::size_t n) { data_.resize(n); }
  // Copy, then move: GCC 12 -Wnonnull misfires on copy-assigning into a provably empty vector.
  void upload(const std::vector<T>& host) { data_ = HostVector<T>(host.begin(), host.end()); }
  void download(std::vector<T>& host) const { host = std::vector<T>(data_.begin(), data_.end()); }
  /// The first n values (n <= size()).
  void download(std::vector<T>& host, std::size_t n) const {
    host.assign(data_.begin(), data_.begin() + n);
  }
  void swap(DeviceArray& other) { data_.swap(other.data_); }
  std::size_t bytes() const { return data_.capacity() * sizeof(T); }

 private:
  HostVector<T> data_;
};

/// CUDA device buffer; keeps its contents on resize. The first allocation is exact; a buffer that
/// grows beyond it gets a quarter more room, so one that keeps growing reallocates rarely.
template <class T>
class DeviceArray<T, CudaSpace> {
 public:
  DeviceArray() = default;
  explicit DeviceArray(std::size_t n) { resize(n); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  DeviceArray(DeviceArray&& o) noexcept { swap(o); }
  DeviceArray& operator=(DeviceArray&& o) noexcept {
    swap(o);
    return *this;
  }
  ~DeviceArray() { cuda::release(ptr_); }

  T* data() { return ptr_; }
  const T* data() const { return ptr_; }
  std::size_t size() const { return size_; }
  void resize(std::size_t n) {
    if (n > capacity_) {
      const std::size_t cap = capacity_ == 0 ? n : n + n / 4;
      T* fresh = static_cast<T*>(cuda::allocate(cap * sizeof(T)));
      if (size_ > 0) cuda::copy_on_device(fresh, ptr_, size_ * sizeof(T));
      cuda::release(ptr_);
      ptr_ = fresh;
      capacity_ = cap;
    }
    size_ = n;
  }
  void upload(const std::vector<T>& host) {
    resize(host.size());
    if (!host.empty()) cuda::copy_to_device(ptr_, host.data(), host.size() * sizeof(T));
  }
  void download(std::vector<T>& host) const { download(host, size_); }
  /// The first n values (n <= size()).
  void download(std::vector<T>& host, std::size_t n) const {
    host.resize(n);
    if (n > 0) cuda::copy_to_host(host.data(), ptr_, n * sizeof(T));
  }
  void swap(DeviceArray& o) {
    std::swap(ptr_, o.ptr_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
  }
  std::size_t bytes() const { return capacity_ * sizeof(T); }

 private:
  T* ptr_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

/// Frees the memory of `a` (size and capacity 0).
template <class T, class Space>
void release(DeviceArray<T, Space>& a) {
  DeviceArray<T, Space>().swap(a);
}

/// Page-locked host buffer, the host end of asynchronous copies (`copy_async`) that stage device
/// buffers for a library that reads host memory only. Grows geometrically; unlike DeviceArray it
/// does not keep its contents when it grows.
template <class T>
class PinnedBuffer {
 public:
  PinnedBuffer() = default;
  PinnedBuffer(const PinnedBuffer&) = delete;
  PinnedBuffer& operator=(const PinnedBuffer&) = delete;
  ~PinnedBuffer() { cuda::release_pinned(ptr_); }

  T* data() { return ptr_; }
  const T* data() const { return ptr_; }
  std::size_t size() const { return size_; }
  void resize(std::size_t n) {
    if (n > capacity_) {
      const std::size_t cap = n + n / 4;
      cuda::release_pinned(ptr_);
      ptr_ = nullptr;  // empty, not dangling, if the allocation below throws
      capacity_ = 0;
      ptr_ = static_cast<T*>(cuda::allocate_pinned(cap * sizeof(T)));
      capacity_ = cap;
    }
    size_ = n;
  }
  std::size_t bytes() const { return capacity_ * sizeof(T); }

 private:
  T* ptr_ = nullptr;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

/// A CUDA stream of its owner's, created on first use. Its work runs after the kernels launched
/// before it and before those launched after it (a blocking stream, CudaMemory.hpp).
class CudaStream {
 public:
  CudaStream() = default;
  CudaStream(const CudaStream&) = delete;
  CudaStream& operator=(const CudaStream&) = delete;
  ~CudaStream() { cuda::destroy_stream(stream_); }

  cuda::Stream get() {
    if (!stream_) stream_ = cuda::create_stream();
    return stream_;
  }
  /// Waits until the work queued on the stream has finished.
  void synchronize() {
    if (stream_) cuda::synchronize(stream_);
  }

 private:
  cuda::Stream stream_ = nullptr;
};

/// Queues on `stream` the copy of the first n elements of `from` into `to` (sized for them).
template <class T>
void copy_async(const DeviceArray<T, CudaSpace>& from, PinnedBuffer<T>& to, std::size_t n,
                CudaStream& stream) {
  if (n > 0) cuda::copy_to_host_async(to.data(), from.data(), n * sizeof(T), stream.get());
}

/// Queues on `stream` the copy of the first n elements of `from` into `to` (sized for them).
template <class T>
void copy_async(const PinnedBuffer<T>& from, DeviceArray<T, CudaSpace>& to, std::size_t n,
                CudaStream& stream) {
  if (n > 0) cuda::copy_to_device_async(to.data(), from.data(), n * sizeof(T), stream.get());
}

}  // namespace gpudem
