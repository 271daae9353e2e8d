#pragma once
/// The count and id checksum of a set of particles: equal for equal id sets whatever their
/// order or the ranks holding them, so a sum over ranks shows whether a particle was lost or
/// duplicated between ranks.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/Config.hpp"

namespace gpudem {

struct ParticleTally {
  std::uint64_t count = 0;
  std::uint64_t id_sum = 0;  ///< Σ splitmix64(id) modulo 2^64 (id_checksum)
};

/// Σ splitmix64(id) modulo 2^64 over the n ids (splitmix64: Steele, Lea & Flood, OOPSLA 2014).
inline std::uint64_t id_checksum(const ParticleId* ids, std::size_t n) {
  std::uint64_t sum = 0;
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t z = ids[k] + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    sum += z ^ (z >> 31);
  }
  return sum;
}

inline ParticleTally tally_of(const std::vector<ParticleId>& ids) {
  return {ids.size(), id_checksum(ids.data(), ids.size())};
}

/// Empty when the tally `found` over `ranks` ranks equals `expected`, else what differs.
inline std::string conservation_problem(const ParticleTally& found, const ParticleTally& expected,
                                        int ranks) {
  if (found.count == expected.count && found.id_sum == expected.id_sum) return {};
  return "particles were lost or duplicated between ranks: " + std::to_string(found.count) +
         " particles on " + std::to_string(ranks) + " ranks where there should be " +
         std::to_string(expected.count) +
         (found.id_sum != expected.id_sum ? " and their ids differ from the expected set" : "");
}

}  // namespace gpudem
