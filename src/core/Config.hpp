#pragma once
/// Build-wide basics: the host/device function marker and the floating-point type.
#include <cstdint>

#if defined(__CUDACC__)
#define GPUDEM_HD __host__ __device__
#else
#define GPUDEM_HD
#endif

namespace gpudem {

/// Floating-point type of particle state and forces (double everywhere for now; the
/// precision policy of docs/architecture.md, "Precision" replaces this single switch when mixed
/// precision lands).
using Real = double;

using ParticleId = std::uint64_t;
using MaterialId = std::uint32_t;

}  // namespace gpudem
