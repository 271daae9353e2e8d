#pragma once
/// A rank's share of rows that every rank can index (particles created on every rank, the
/// rows of a file): consecutive rows, as even as the count allows, in rank order.
#include <cstddef>
#include <vector>

#include "core/ContactHistory.hpp"
#include "core/ParticleStore.hpp"

namespace gpudem {

/// Rows [first, first + count) of a table.
struct RowRange {
  std::size_t first = 0;
  std::size_t count = 0;
};

/// Rank `rank`'s share of `rows` rows on `ranks` ranks: [⌊rows·rank/ranks⌋,
/// ⌊rows·(rank+1)/ranks⌋).
inline RowRange share_of_rows(std::size_t rows, int rank, int ranks) {
  const auto n = static_cast<std::size_t>(ranks);
  const auto bound = [&](int r) {  // ⌊rows·r/ranks⌋ without overflow
    const auto k = static_cast<std::size_t>(r);
    return rows / n * k + rows % n * k / n;
  };
  return {bound(rank), bound(rank + 1) - bound(rank)};
}

/// Part `index` of `count` near-equal parts of a table's rows, in order (the whole table by
/// default): what each rank reads of a file that every rank opens.
struct FilePart {
  int index = 0;
  int count = 1;
  RowRange rows_of(std::size_t rows) const { return share_of_rows(rows, index, count); }
};

/// Rows `range` of `all` (`width` values per row); empty when `all` is.
template <class T>
std::vector<T> rows_of(const std::vector<T>& all, RowRange range, std::size_t width = 1) {
  if (all.empty()) return {};
  const auto first = all.begin() + static_cast<std::ptrdiff_t>(range.first * width);
  return std::vector<T>(first, first + static_cast<std::ptrdiff_t>(range.count * width));
}

/// Rank `rank`'s share of the particles `all` on `ranks` ranks.
inline ParticleStore share_of(const ParticleStore& all, int rank, int ranks) {
  const RowRange r = share_of_rows(all.size(), rank, ranks);
  ParticleStore p;
  for_each_particle_field([&](auto field) { field.of(p) = rows_of(field.of(all), r); });
  return p;
}

/// Rank `rank`'s share of each kind of record of `all` on `ranks` ranks.
inline ContactHistory share_of(const ContactHistory& all, int rank, int ranks) {
  ContactHistory h;
  h.width = all.width;
  const RowRange pairs = share_of_rows(all.pair_owner.size(), rank, ranks);
  h.pair_owner = rows_of(all.pair_owner, pairs);
  h.pair_partner = rows_of(all.pair_partner, pairs);
  h.pair_values = rows_of(all.pair_values, pairs, all.width);
  const RowRange walls = share_of_rows(all.wall_owner.size(), rank, ranks);
  h.wall_owner = rows_of(all.wall_owner, walls);
  h.wall_index = rows_of(all.wall_index, walls);
  h.wall_values = rows_of(all.wall_values, walls, all.width);
  const RowRange meshes = share_of_rows(all.mesh_owner.size(), rank, ranks);
  h.mesh_owner = rows_of(all.mesh_owner, meshes);
  h.mesh_triangle = rows_of(all.mesh_triangle, meshes);
  h.mesh_values = rows_of(all.mesh_values, meshes, all.width);
  return h;
}

}  // namespace gpudem
