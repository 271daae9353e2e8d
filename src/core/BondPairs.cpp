#include "core/BondPairs.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "core/CsvReader.hpp"
#include "core/InputError.hpp"

namespace gpudem {
namespace {

/// The index of column `name` in the header; throws naming the file when it is missing.
std::size_t column_of(const CsvReader& csv, const std::string& name) {
  const std::vector<std::string>& header = csv.header();
  const auto found = std::find(header.begin(), header.end(), name);
  if (found == header.end())
    throw InputError(csv.path(), 1, "",
                     "missing column '" + name + "': the header must name id_a and id_b");
  return static_cast<std::size_t>(found - header.begin());
}

/// Field `field` of column `column` as a particle id.
ParticleId id_of(const CsvReader& csv, const std::string& field, const std::string& column) {
  const double value = csv.number(field, column);
  if (value < 0 || value != std::floor(value) || value > 9.007199254740992e15)
    throw InputError(csv.path(), csv.line(), column,
                     "'" + field + "' is not a particle id (an integer >= 0)");
  return static_cast<ParticleId>(value);
}

}  // namespace

std::vector<ListedBond> read_bond_pairs(const std::string& path) {
  CsvReader csv(path);
  const std::size_t a = column_of(csv, "id_a"), b = column_of(csv, "id_b");
  std::vector<ListedBond> pairs;
  std::vector<std::string> fields;
  while (csv.next(fields)) {
    const ParticleId x = id_of(csv, fields[a], "id_a"), y = id_of(csv, fields[b], "id_b");
    if (x == y)
      throw InputError(path, csv.line(), "id_b",
                       "particle " + std::to_string(x) + " is paired with itself");
    pairs.push_back({std::min(x, y), std::max(x, y), csv.line()});
  }
  if (pairs.empty()) throw InputError(path, csv.line(), "", "lists no pair to bond");
  std::sort(pairs.begin(), pairs.end(), [](const ListedBond& p, const ListedBond& q) {
    return std::tie(p.lower, p.higher, p.line) < std::tie(q.lower, q.higher, q.line);
  });
  for (std::size_t k = 1; k < pairs.size(); ++k)
    if (pairs[k].lower == pairs[k - 1].lower && pairs[k].higher == pairs[k - 1].higher)
      throw InputError(path, pairs[k].line, "",
                       "the pair " + std::to_string(pairs[k].lower) + ", " +
                           std::to_string(pairs[k].higher) + " is listed twice (also on line " +
                           std::to_string(pairs[k - 1].line) + ")");
  return pairs;
}

}  // namespace gpudem
