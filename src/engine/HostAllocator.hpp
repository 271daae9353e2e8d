#pragma once
/// The allocator of the host's particle, list and history buffers. A buffer of a huge page
/// (2 MiB) or more starts on a huge-page boundary and asks the kernel for transparent huge pages
/// (madvise MADV_HUGEPAGE, which a kernel in `always` or `madvise` mode honours when it can): the
/// force sweep's scattered reads of partners and records then miss the TLB less often
/// (docs/performance.md, "Huge pages, and partners beside the entries"). A smaller buffer is an
/// ordinary allocation. The advice is a hint; where the kernel does not take it, the pages stay
/// small and nothing else changes. Host code only.
#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace gpudem {

/// The size of a huge page on Linux with 4 KiB base pages (x86-64; AArch64 with 4 KiB pages)
/// [bytes]: a buffer from this size on asks for huge pages. On AArch64 kernels with 64 KiB base
/// pages a huge page is 512 MiB, and the advice then gains nothing.
inline constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;

/// `bytes` aligned to `alignment`, on huge pages from kHugePageBytes on (aligned to a huge page,
/// which covers any alignment up to it).
inline void* allocate_host_bytes(std::size_t bytes, std::size_t alignment) {
  if (bytes < kHugePageBytes) return ::operator new(bytes, std::align_val_t(alignment));
  void* p = nullptr;
  if (posix_memalign(&p, kHugePageBytes, bytes) != 0) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(p, bytes, MADV_HUGEPAGE);  // a hint: refused, the pages stay small
#endif
  return p;
}

/// Frees what allocate_host_bytes(bytes, alignment) returned.
inline void release_host_bytes(void* p, std::size_t bytes, std::size_t alignment) noexcept {
  if (bytes < kHugePageBytes)
    ::operator delete(p, std::align_val_t(alignment));
  else
    std::free(p);
}

/// The standard allocator's interface over allocate_host_bytes.
template <class T>
struct HostAllocator {
  using value_type = T;
  HostAllocator() = default;
  template <class U>
  HostAllocator(const HostAllocator<U>&) noexcept {}  // NOLINT: rebinding converts implicitly
  T* allocate(std::size_t n) {
    return static_cast<T*>(allocate_host_bytes(n * sizeof(T), alignof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    release_host_bytes(p, n * sizeof(T), alignof(T));
  }
};

/// Any two HostAllocators free each other's buffers: they hold no state.
template <class T, class U>
bool operator==(const HostAllocator<T>&, const HostAllocator<U>&) {
  return true;
}
/// Never: see operator==.
template <class T, class U>
bool operator!=(const HostAllocator<T>&, const HostAllocator<U>&) {
  return false;
}

/// A host buffer that grows with the particles (HostAllocator).
template <class T>
using HostVector = std::vector<T, HostAllocator<T>>;

}  // namespace gpudem
