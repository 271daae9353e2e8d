#pragma once
/// Build-wide basics: the host/device function marker and the floating-point type.
#include <cstdint>

#if defined(__CUDACC__)
#define GPUDEM_HD __host__ __device__
/// Before a GPUDEM_HD template that calls a callable it is given: the call is checked where the
/// template is instantiated, so host-only callables may be passed from host code.
#define GPUDEM_HD_CALLS_ANY _Pragma("nv_exec_check_disable")
/// A GPUDEM_HD function that the device code calls instead of inlining: a law-independent step
/// of every law's kernels (the mesh contact search) is then compiled once per translation unit
/// instead of once per kernel. Host code inlines as the compiler sees fit.
#define GPUDEM_HD_CALLED __host__ __device__ __noinline__
#else
#define GPUDEM_HD
#define GPUDEM_HD_CALLS_ANY
#define GPUDEM_HD_CALLED
#endif

/// On a per-particle kernel body whose callees the host compiler should inline whole (the
/// contact sweep: the law, the contact's description and its visitor), so that the contact's
/// record stays in registers; device code inlines them anyway. A build with AddressSanitizer
/// (the compiler defines __SANITIZE_ADDRESS__) leaves inlining to the compiler: flattened and
/// instrumented, a host force compute unit took three times as long to compile, and speed is
/// not what it is built for.
#if defined(__CUDA_ARCH__) || !defined(__GNUC__) || defined(__SANITIZE_ADDRESS__)
#define GPUDEM_HOST_FLATTEN
#else
#define GPUDEM_HOST_FLATTEN __attribute__((flatten))
#endif

namespace gpudem {

/// Floating-point type of particle state and forces (double everywhere for now; the
/// precision policy of docs/architecture.md, "Precision" replaces this single switch when mixed
/// precision lands).
using Real = double;

using ParticleId = std::uint64_t;
using MaterialId = std::uint32_t;

}  // namespace gpudem
