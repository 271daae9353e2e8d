#pragma once
/// The pairs a [[bond]] table lists in a CSV file (docs/input.md, "[[bond]]"): columns `id_a`
/// and `id_b`, the global ids of the two particles of each bond.
#include <cstdint>
#include <string>
#include <vector>

#include "core/Config.hpp"

namespace gpudem {

/// One listed bond: its ids, lower first, and the line of the file that lists it.
struct ListedBond {
  ParticleId lower = 0, higher = 0;
  int line = 0;
};

/// The pairs of `path`, ordered by (lower, higher). Throws InputError naming the file, line and
/// column for a file that cannot be read, a missing column, an id that is not an integer >= 0,
/// a particle paired with itself, a pair listed twice (naming both lines) or no pair at all.
std::vector<ListedBond> read_bond_pairs(const std::string& path);

}  // namespace gpudem
