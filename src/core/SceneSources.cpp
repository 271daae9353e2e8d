// Scene loading: the [[source]] tables (box insertion, CSV files, saved beds) with their radius
// distributions and regions.
#include "core/SceneSources.hpp"

#include <string>
#include <vector>

#include "core/InputError.hpp"
#include "core/SceneReading.hpp"

namespace gpudem::scene_reading {
namespace {

/// radius = {distribution = "uniform", mean, spread}: radii in mean ± spread.
RadiusDistribution read_uniform_radius(const TableReader& table) {
  table.allow_only({"distribution", "mean", "spread"});
  RadiusDistribution r;
  r.kind = RadiusDistributionKind::Uniform;
  r.mean = table.number("mean", positive("m"));
  r.spread = table.number("spread", non_negative("m"), 0);
  if (!(r.spread < r.mean)) {
    table.fail_found("spread", "a number < mean = " + format_number(r.mean) +
                                   " [m] so that every radius is > 0");
  }
  return r;
}

/// radius = {distribution = "normal", mean, stddev, min, max}: truncated normal.
RadiusDistribution read_normal_radius(const TableReader& table) {
  table.allow_only({"distribution", "mean", "stddev", "min", "max"});
  RadiusDistribution r;
  r.kind = RadiusDistributionKind::TruncatedNormal;
  r.mean = table.number("mean", positive("m"));
  r.stddev = table.number("stddev", positive("m"));
  r.min = table.number("min", positive("m"));
  r.max = table.number("max", positive("m"));
  const std::string mean = format_number(r.mean);
  if (r.min > r.mean) table.fail_found("min", "a number <= mean = " + mean + " [m]");
  if (r.max < r.mean) table.fail_found("max", "a number >= mean = " + mean + " [m]");
  return r;
}

/// radius = {distribution = "discrete", values, weights}: radii drawn from a list.
RadiusDistribution read_discrete_radius(const TableReader& table) {
  table.allow_only({"distribution", "values", "weights"});
  RadiusDistribution r;
  r.kind = RadiusDistributionKind::Discrete;
  r.values = table.numbers("values", positive("m"));
  r.weights = table.has("weights") ? table.numbers("weights", positive())
                                   : std::vector<double>(r.values.size(), 1.0);
  if (r.weights.size() != r.values.size()) {
    table.fail("weights", "expected as many weights as values (" + std::to_string(r.values.size()) +
                              "), got " + std::to_string(r.weights.size()));
  }
  return r;
}

}  // namespace

RadiusDistribution read_radius(const TableReader& source) {
  if (source.has("radius") && source.value("radius").is_table()) {
    const TableReader table = source.table("radius");
    const std::string kind =
        table.choice("distribution", {"uniform", "normal", "discrete"}, "uniform");
    if (kind == "normal") return read_normal_radius(table);
    if (kind == "discrete") return read_discrete_radius(table);
    return read_uniform_radius(table);
  }
  RadiusDistribution r;
  r.mean = source.number("radius", positive("m"));
  return r;
}

namespace {

/// The box `region` of a source, which must lie inside the domain (touching it is allowed).
void read_region(const TableReader& source, const DomainSettings& domain, ParticleSource& s) {
  const TableReader region = source.table("region");
  region.allow_only({"min", "max"});
  s.region_min = region.vec3("min", "m");
  s.region_max = region.vec3("max", "m");
  require_extent(region, "max", s.region_min, s.region_max, "the source region is empty");
  for (int k = 0; k < 3; ++k) {
    const double lo = axis(s.region_min, k), hi = axis(s.region_max, k);
    if (lo < axis(domain.min, k) || hi > axis(domain.max, k)) {
      source.fail("region", std::string("source region lies outside the domain on ") + "xyz"[k] +
                                ": [" + format_number(lo) + ", " + format_number(hi) +
                                "] is not inside [" + format_number(axis(domain.min, k)) + ", " +
                                format_number(axis(domain.max, k)) + "]");
    }
  }
}

/// Keys that only box (region) sources take.
const std::vector<std::string> kBoxOnlyKeys = {"region", "count",    "volume_fraction",
                                               "radius", "velocity", "placement"};

ParticleSource read_box_source(const TableReader& table, const Scene& scene) {
  ParticleSource s;
  s.kind = SourceKind::Box;
  read_region(table, scene.domain, s);
  if (table.has("count") && table.has("volume_fraction")) {
    table.fail("volume_fraction", "give either count or volume_fraction, not both");
  }
  if (table.has("volume_fraction")) {
    s.volume_fraction = table.number("volume_fraction", interval(0, true, 0.6, false));
  } else if (table.has("count")) {
    s.count = static_cast<std::uint64_t>(table.integer("count", positive()));
  } else {
    table.fail("count", "missing 'count' or 'volume_fraction' in [[insert]] (give exactly one)");
  }
  s.radius = read_radius(table);
  s.material = material_index(table, "material", scene.materials);
  s.velocity = table.vec3("velocity", "m/s", s.velocity);
  s.placement = named_choice(table, "placement", {"sequential", "tiled"}, s.placement);
  return s;
}

/// Fails on the first of `keys` the table holds, saying why it does not belong there.
void refuse_keys(const TableReader& table, const std::vector<std::string>& keys,
                 const std::string& why) {
  for (const std::string& key : keys)
    if (table.has(key)) table.fail(key, "'" + key + "' " + why);
}

/// A CSV source; its file is resolved relative to the scene file's directory, not opened.
ParticleSource read_csv_source(const TableReader& table, const Scene& scene) {
  refuse_keys(table, kBoxOnlyKeys,
              "belongs to region sources; a csv source takes only csv and material");
  ParticleSource s;
  s.kind = SourceKind::Csv;
  s.csv_file = path_beside_scene(table, "csv", scene);
  s.material = table.has("material") ? material_index(table, "material", scene.materials) : 0;
  return s;
}

/// A bed source: the particles of a saved bed file (resolved like a CSV file, not opened).
ParticleSource read_bed_source(const TableReader& table, const Scene& scene) {
  std::vector<std::string> other_keys = kBoxOnlyKeys;
  other_keys.push_back("material");
  refuse_keys(table, other_keys,
              "does not apply to a bed source, whose particles keep their own values; a bed "
              "source takes only bed");
  ParticleSource s;
  s.kind = SourceKind::Bed;
  s.bed_file = path_beside_scene(table, "bed", scene);
  s.bed_line = table.line("bed");
  return s;
}

/// The one source kind an [[insert]] entry names by its `region`, `csv` or `bed` key.
SourceKind source_kind(const TableReader& table) {
  const std::pair<std::string, SourceKind> kinds[] = {
      {"region", SourceKind::Box}, {"csv", SourceKind::Csv}, {"bed", SourceKind::Bed}};
  const std::pair<std::string, SourceKind>* chosen = nullptr;
  for (const auto& kind : kinds) {
    if (!table.has(kind.first)) continue;
    if (chosen) {
      table.fail(kind.first, "an [[insert]] takes either " + kind.first + " or " + chosen->first +
                                 ", not both");
    }
    chosen = &kind;
  }
  if (!chosen) {
    table.fail("region",
               "missing 'region' (random insertion in a box), 'csv' (particles from a file) or "
               "'bed' (the particles of a saved bed) in [[insert]]");
  }
  return chosen->second;
}

ParticleSource read_source(const TableReader& table, const Scene& scene) {
  table.allow_only({"csv", "region", "bed", "count", "volume_fraction", "radius", "material",
                    "velocity", "placement"});
  switch (source_kind(table)) {
    case SourceKind::Csv:
      return read_csv_source(table, scene);
    case SourceKind::Bed:
      return read_bed_source(table, scene);
    case SourceKind::Box:
      break;
  }
  return read_box_source(table, scene);
}

}  // namespace

std::vector<ParticleSource> read_sources(const TableReader& root, const Scene& scene) {
  std::vector<ParticleSource> sources;
  const std::vector<TableReader> tables = root.array_of_tables("insert");
  for (std::size_t i = 0; i < tables.size(); ++i) {
    sources.push_back(read_source(tables[i], scene));
    for (std::size_t j = 0; j < i; ++j) {
      if (sources[i].kind == SourceKind::Bed && sources[j].kind == SourceKind::Bed) {
        tables[i].fail("bed", "a scene takes at most one bed source (also given by insert[" +
                                  std::to_string(j) + "])");
      }
    }
  }
  return sources;
}
}  // namespace gpudem::scene_reading
