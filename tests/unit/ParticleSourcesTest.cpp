// Particle sources: radius distributions against their closed forms, random non-overlapping
// box insertion (by count and by volume fraction; what both placements must do, and the
// sequential placement's own bounds), and CSV import with its error reports.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "core/InputError.hpp"
#include "core/ParticleSources.hpp"
#include "support/InsertionChecks.hpp"
#include "support/TestPaths.hpp"

namespace gpudem {
namespace {

using test::ball_volume;
using test::box;
using test::discrete;
using test::expect_inside;
using test::expect_no_overlaps;
using test::uniform;

Scene make_scene(std::uint64_t seed = 7) { return test::insertion_scene(seed); }

ParticleSource csv_source(const std::string& name) {
  ParticleSource s;
  s.kind = SourceKind::Csv;
  s.csv_file = test::source_dir() + "/tests/data/csv/" + name;
  return s;
}

double mean_of(const std::vector<double>& x) {
  double s = 0;
  for (double v : x) s += v;
  return s / static_cast<double>(x.size());
}

double variance_of(const std::vector<double>& x) {
  const double m = mean_of(x);
  double s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return s / static_cast<double>(x.size() - 1);
}

// ---------------------------------------------------------------- radius distributions

constexpr std::size_t samples = 200000;

TEST(RadiusDistribution, UniformMatchesMeanVarianceAndBounds) {
  const double mean = 2e-3, spread = 1e-3;
  std::mt19937_64 rng(1);
  const std::vector<double> r = sample_radii(uniform(mean, spread), samples, rng);
  ASSERT_EQ(r.size(), samples);
  const double n = static_cast<double>(samples);
  // Mean: sigma = spread/sqrt(3); variance spread^2/3 with standard error
  // spread^2 sqrt((mu4 - sigma^4)/n) = spread^2 sqrt(4/45/n). Tolerances: 5 standard errors.
  EXPECT_NEAR(mean_of(r), mean, 5 * spread / std::sqrt(3 * n));
  EXPECT_NEAR(variance_of(r), spread * spread / 3, 5 * spread * spread * std::sqrt(4 / 45.0 / n));
  const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
  EXPECT_GE(*lo, mean - spread);
  EXPECT_LE(*hi, mean + spread);
  // The extremes reach within 25/n of the width of the bounds (fails with probability e^-25).
  EXPECT_LT(*lo - (mean - spread), 2 * spread * 25 / n);
  EXPECT_GT(*hi - (mean + spread), -2 * spread * 25 / n);
}

TEST(RadiusDistribution, TruncatedNormalMatchesClosedFormMean) {
  RadiusDistribution d;
  d.kind = RadiusDistributionKind::TruncatedNormal;
  d.mean = 1e-3;
  d.stddev = 0.4e-3;
  d.min = 0.5e-3;
  d.max = 2e-3;
  std::mt19937_64 rng(2);
  const std::vector<double> r = sample_radii(d, samples, rng);
  // Truncated normal moments (Johnson, Kotz & Balakrishnan 1994, §10.1), a = (min-mean)/sd,
  // b = (max-mean)/sd, Z = Phi(b) - Phi(a): mean + sd (phi(a) - phi(b))/Z and variance
  // sd^2 [1 + (a phi(a) - b phi(b))/Z - ((phi(a) - phi(b))/Z)^2].
  const auto phi = [](double x) { return std::exp(-x * x / 2) / std::sqrt(2 * test::kPi); };
  const auto Phi = [](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); };
  const double a = (d.min - d.mean) / d.stddev, b = (d.max - d.mean) / d.stddev;
  const double z = Phi(b) - Phi(a), shift = (phi(a) - phi(b)) / z;
  const double expected_mean = d.mean + d.stddev * shift;
  const double expected_var =
      d.stddev * d.stddev * (1 + (a * phi(a) - b * phi(b)) / z - shift * shift);
  const double n = static_cast<double>(samples);
  EXPECT_NEAR(mean_of(r), expected_mean, 5 * std::sqrt(expected_var / n));
  // Relative standard error of a sample variance: sqrt((kurtosis - 1)/n) <= sqrt(2/n) here,
  // truncation making the distribution lighter-tailed than the normal (kurtosis 3).
  EXPECT_NEAR(variance_of(r), expected_var, 5 * std::sqrt(2 / n) * expected_var);
  EXPECT_GE(*std::min_element(r.begin(), r.end()), d.min);
  EXPECT_LE(*std::max_element(r.begin(), r.end()), d.max);
}

TEST(RadiusDistribution, DiscreteFrequenciesMatchWeights) {
  const RadiusDistribution d = discrete({1e-3, 2e-3, 5e-3}, {2, 0, 6});
  std::mt19937_64 rng(3);
  std::map<double, double> seen;
  for (double r : sample_radii(d, samples, rng)) seen[r] += 1;
  EXPECT_EQ(seen.size(), 2u);  // the zero-weight value never appears
  const double n = static_cast<double>(samples);
  for (const auto& [value, p] : {std::pair{1e-3, 0.25}, std::pair{5e-3, 0.75}})
    EXPECT_NEAR(seen[value] / n, p, 5 * std::sqrt(p * (1 - p) / n)) << "radius " << value;
}

TEST(RadiusDistribution, DiscreteWithoutWeightsIsEquallyLikely) {
  std::mt19937_64 rng(4);
  std::map<double, double> seen;
  for (double r : sample_radii(discrete({1e-3, 3e-3}, {}), samples, rng)) seen[r] += 1;
  const double n = static_cast<double>(samples);
  EXPECT_NEAR(seen[1e-3] / n, 0.5, 5 * std::sqrt(0.25 / n));
}

TEST(RadiusDistribution, BoundsOfEachKind) {
  EXPECT_DOUBLE_EQ(min_radius(uniform(2e-3, 0.5e-3)), 1.5e-3);
  EXPECT_DOUBLE_EQ(max_radius(uniform(2e-3, 0.5e-3)), 2.5e-3);
  RadiusDistribution normal;
  normal.kind = RadiusDistributionKind::TruncatedNormal;
  normal.min = 1e-3;
  normal.max = 4e-3;
  EXPECT_DOUBLE_EQ(min_radius(normal), 1e-3);
  EXPECT_DOUBLE_EQ(max_radius(normal), 4e-3);
  const RadiusDistribution d = discrete({3e-3, 0.5e-3, 1e-3, 9e-3}, {1, 1, 1, 0});
  EXPECT_DOUBLE_EQ(min_radius(d), 0.5e-3);
  EXPECT_DOUBLE_EQ(max_radius(d), 3e-3);  // 9e-3 has weight 0
}

TEST(RadiusDistribution, UnsampleableDistributionsAreRefused) {
  std::mt19937_64 rng(5);
  EXPECT_THROW(sample_radii(discrete({1e-3}, {0}), 10, rng), std::invalid_argument);
  RadiusDistribution far_tail;
  far_tail.kind = RadiusDistributionKind::TruncatedNormal;
  far_tail.mean = 1e-3;
  far_tail.stddev = 1e-4;
  far_tail.min = 2e-3;  // ten standard deviations out
  far_tail.max = 3e-3;
  EXPECT_THROW(sample_radii(far_tail, 10, rng), std::invalid_argument);
}

// ---------------------------------------------------------------- box insertion

// Count, containment, overlaps, state and ids of a box fill that started at `first`.
/// The box-insertion tests both placements must pass.
class BoxPlacement : public ::testing::TestWithParam<Placement> {
 protected:
  /// `scene` with every box source placed by GetParam().
  Scene placed(Scene scene) const {
    for (ParticleSource& s : scene.sources) s.placement = GetParam();
    return scene;
  }
};

INSTANTIATE_TEST_SUITE_P(Placements, BoxPlacement,
                         ::testing::Values(Placement::Sequential, Placement::Tiled),
                         [](const auto& info) {
                           return info.param == Placement::Tiled ? "tiled" : "sequential";
                         });

void expect_valid_box_fill(const Scene& scene, const ParticleStore& store, std::size_t first) {
  const ParticleSource& src = scene.sources.back();
  ASSERT_EQ(store.size(), first + src.count);
  expect_inside(store, first, store.size(), src.region_min, src.region_max);
  expect_no_overlaps(store, first);
  const double density = scene.materials[src.material].density;
  for (std::size_t n = first; n < store.size(); ++n) {
    const Real4& v = store.velocity_inv_mass[n];
    const double r = store.position_radius[n].w;
    EXPECT_EQ(store.id[n], n);
    EXPECT_EQ(store.material[n], src.material);
    EXPECT_EQ(v.x, src.velocity.x);
    EXPECT_EQ(v.z, src.velocity.z);
    EXPECT_EQ(norm2(store.angular_velocity[n]), 0.0);
    EXPECT_NEAR(v.w * ball_volume(r) * density, 1.0, 1e-12);
  }
}

TEST_P(BoxPlacement, DiscreteTenToOneByCount) {
  Scene scene = make_scene();
  scene.sources.push_back(
      box({0.1, 0.2, 0.0}, {0.3, 0.4, 0.2}, 3000, discrete({1e-3, 1e-2}, {0.9, 0.1})));
  scene.sources.back().material = 1;
  scene.sources.back().velocity = {0.5, 0, -1};
  ParticleStore store;
  create_particles(placed(scene), store);
  expect_valid_box_fill(scene, store, 0);
  const auto large = std::count_if(store.position_radius.begin(), store.position_radius.end(),
                                   [](const Real4& p) { return p.w == 1e-2; });
  EXPECT_GT(large, 200);  // binomial(3000, 0.1): mean 300, sd 16
  EXPECT_LT(large, 400);
}

TEST_P(BoxPlacement, UniformTenToOneByCount) {
  Scene scene = make_scene();
  scene.sources.push_back(box({0, 0, 0}, {0.025, 0.025, 0.025}, 3000, uniform(0.55e-3, 0.45e-3)));
  ParticleStore store;
  create_particles(placed(scene), store);
  expect_valid_box_fill(scene, store, 0);
}

TEST_P(BoxPlacement, SameSeedSameParticlesOtherSeedOthers) {
  const auto fill = [this](std::uint64_t seed) {
    Scene scene = make_scene(seed);
    scene.sources.push_back(box({0, 0, 0}, {0.05, 0.05, 0.05}, 500, uniform(1e-3, 0.5e-3)));
    ParticleStore store;
    create_particles(placed(scene), store);
    std::vector<double> flat;
    for (const Real4& p : store.position_radius) flat.insert(flat.end(), {p.x, p.y, p.z, p.w});
    return flat;
  };
  const std::vector<double> a = fill(11);
  EXPECT_EQ(a, fill(11));
  EXPECT_NE(a, fill(12));
}

TEST(BoxInsertion, VolumeFractionReachedWithinOneParticle) {
  Scene scene = make_scene();
  const Vec3 lo{0, 0, 0}, hi{0.04, 0.04, 0.04};
  const RadiusDistribution radius = uniform(1e-3, 0.5e-3);
  scene.sources.push_back(box(lo, hi, 0, radius));
  scene.sources.back().volume_fraction = 0.3;
  ParticleStore store;
  create_particles(scene, store);
  double solid = 0;
  for (const Real4& p : store.position_radius) solid += ball_volume(p.w);
  const double region = 0.04 * 0.04 * 0.04;
  EXPECT_GE(solid / region, 0.3);
  EXPECT_LE(solid / region, 0.3 + ball_volume(max_radius(radius)) / region);
  expect_inside(store, 0, store.size(), lo, hi);
  expect_no_overlaps(store);
}

TEST(BoxInsertion, ImpossibleRequestNamesTheSource) {
  Scene scene = make_scene();
  scene.sources.push_back(box({0.5, 0.5, 0.5}, {0.6, 0.6, 0.6}, 10, uniform(1e-3, 0)));
  // 150 spheres of 5 mm fill 0.52 of the box: under the densest packing (at most 176), past
  // where random insertion jams.
  scene.sources.push_back(box({0, 0, 0}, {0.05, 0.05, 0.05}, 150, uniform(5e-3, 0)));
  ParticleStore store;
  try {
    create_particles(scene, store);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "insert[1]");
    EXPECT_NE(std::string(e.what()).find("could only place"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("of 150 particles"), std::string::npos) << e.what();
  }
}

/// More spheres than fit at the densest packing of the smallest radius (π/√18 of the region's
/// volume) are refused before any is drawn, with that capacity in the message; the second source
/// is checked on its own region.
TEST(BoxInsertion, CountBeyondTheDensestPackingIsRefusedBeforePlacement) {
  Scene scene = make_scene();
  scene.sources.push_back(box({0, 0, 0}, {0.01, 0.01, 0.01}, 10, uniform(1e-3, 0)));
  scene.sources.push_back(box({0, 0, 0}, {0.1, 0.2, 0.1}, 600000000, uniform(1e-3, 0.5e-3)));
  // 0.74048 × 2e-3 m³ / (4/3 π (0.5e-3 m)³) = 2,828,427.1
  const double capacity = std::floor(M_PI / std::sqrt(18.0) * 2e-3 / (4.0 / 3.0 * M_PI * 1.25e-10));
  ASSERT_EQ(capacity, 2828427.0);
  ParticleStore store;
  try {
    create_particles(scene, store);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "insert[1].count");
    const std::string what = e.what();
    EXPECT_NE(what.find("count = 600000000 is more than the region can hold: at most 2828427 "
                        "spheres of the smallest radius 0.0005 m"),
              std::string::npos)
        << what;
  }
  EXPECT_TRUE(store.position_radius.empty());
  scene.sources.back().count = 2828428;
  EXPECT_THROW(create_particles(scene, store), InputError);
}

TEST_P(BoxPlacement, RegionThinnerThanADiameterIsRefused) {
  Scene scene = make_scene();
  scene.sources.push_back(box({0, 0, 0}, {0.1, 0.1, 0.001}, 1, uniform(1e-3, 0)));
  ParticleStore store;
  EXPECT_THROW(create_particles(placed(scene), store), InputError);
}

TEST_P(BoxPlacement, SecondSourceAvoidsTheFirst) {
  Scene scene = make_scene();
  scene.sources.push_back(box({0, 0, 0}, {0.1, 0.1, 0.1}, 2000, uniform(2e-3, 1e-3)));
  scene.sources.push_back(box({0.05, 0, 0}, {0.15, 0.1, 0.1}, 2000, uniform(2e-3, 1e-3)));
  ParticleStore store;
  create_particles(placed(scene), store);
  ASSERT_EQ(store.size(), 4000u);
  expect_inside(store, 0, 2000, scene.sources[0].region_min, scene.sources[0].region_max);
  expect_inside(store, 2000, 4000, scene.sources[1].region_min, scene.sources[1].region_max);
  expect_no_overlaps(store);
}

TEST_P(BoxPlacement, AvoidsParticlesAlreadyInTheStoreAndContinuesTheirIds) {
  Scene scene = make_scene();
  scene.sources.push_back(box({0, 0, 0}, {0.06, 0.06, 0.06}, 1500, uniform(1e-3, 0.2e-3)));
  ParticleStore store;
  store.add(0, {0.03, 0.03, 0.03}, 0.02, 0, {}, 1.0);   // large sphere in the middle
  store.add(1, {0.065, 0.03, 0.03}, 0.01, 0, {}, 1.0);  // centre outside, reaching in
  create_particles(placed(scene), store);
  expect_valid_box_fill(scene, store, 2);
  expect_no_overlaps(store);
}

TEST_P(BoxPlacement, AvoidsThePeriodicImagesOfParticlesCrossingAPeriodicFace) {
  Scene scene = make_scene();
  scene.domain.periodic = {true, true, false};
  scene.sources.push_back(box({0, 0, 0}, {0.06, 0.06, 0.06}, 1500, uniform(1e-3, 0.2e-3)));
  ParticleStore store;
  store.add(0, {0.995, 0.03, 0.03}, 0.01, 0, {}, 1.0);    // across x = 1: an image at x = -0.005
  store.add(1, {0.998, 0.998, 0.04}, 0.008, 0, {}, 1.0);  // across the corner x = y = 1
  store.add(2, {1.004, 0.01, 0.01}, 0.006, 0, {}, 1.0);   // centre beyond x = 1, wrapped to 0.004
  create_particles(placed(scene), store);
  expect_valid_box_fill(scene, store, 3);
  ParticleStore with_images = store;  // the images in the box's corner, placed by hand
  with_images.add(3, {-0.005, 0.03, 0.03}, 0.01, 0, {}, 1.0);
  with_images.add(4, {-0.002, -0.002, 0.04}, 0.008, 0, {}, 1.0);
  with_images.add(5, {0.998, -0.002, 0.04}, 0.008, 0, {}, 1.0);
  with_images.add(6, {-0.002, 0.998, 0.04}, 0.008, 0, {}, 1.0);
  with_images.add(7, {0.004, 0.01, 0.01}, 0.006, 0, {}, 1.0);
  expect_no_overlaps(with_images, 3);
}

TEST_P(BoxPlacement, NeitherCountNorVolumeFractionIsRefused) {
  Scene scene = make_scene();
  scene.sources.push_back(box({0, 0, 0}, {0.1, 0.1, 0.1}, 0, uniform(1e-3, 0)));
  ParticleStore store;
  EXPECT_THROW(create_particles(placed(scene), store), InputError);
}

// ---------------------------------------------------------------- CSV import

TEST(CsvImport, AllColumns) {
  Scene scene = make_scene();
  scene.sources.push_back(csv_source("full.csv"));
  ParticleStore store;
  store.add(0, {0.9, 0.9, 0.9}, 0.01, 0, {}, 1.0);
  create_particles(scene, store);
  ASSERT_EQ(store.size(), 3u);
  EXPECT_EQ(store.id[1], 1u);
  EXPECT_EQ(store.id[2], 2u);
  EXPECT_DOUBLE_EQ(store.position_radius[1].y, 0.2);
  EXPECT_DOUBLE_EQ(store.position_radius[1].w, 0.01);
  EXPECT_EQ(store.material[1], 0u);  // "soil"
  EXPECT_EQ(store.material[2], 1u);  // index 1
  EXPECT_DOUBLE_EQ(store.velocity_inv_mass[1].y, 2.0);
  EXPECT_DOUBLE_EQ(store.velocity_inv_mass[2].z, -1.0);
  EXPECT_NEAR(store.velocity_inv_mass[2].w * ball_volume(0.02) * 7800.0, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(store.angular_velocity[1].x, 10.0);
  EXPECT_DOUBLE_EQ(store.angular_velocity[1].y, -20.0);
  EXPECT_DOUBLE_EQ(store.angular_velocity[1].z, 30.0);
  EXPECT_DOUBLE_EQ(store.angular_velocity[2].y, 0.0);
}

TEST(CsvImport, RequiredColumnsOnlyTakeTheSourceDefaults) {
  Scene scene = make_scene();
  scene.sources.push_back(csv_source("minimal.csv"));  // CRLF line ends, blank lines
  scene.sources.back().material = 1;
  scene.sources.back().velocity = {0, 0, -2};
  ParticleStore store;
  create_particles(scene, store);
  ASSERT_EQ(store.size(), 2u);
  EXPECT_DOUBLE_EQ(store.position_radius[1].x, 0.75);
  EXPECT_DOUBLE_EQ(store.position_radius[1].w, 0.004);
  EXPECT_EQ(store.material[0], 1u);
  EXPECT_DOUBLE_EQ(store.velocity_inv_mass[0].z, -2.0);
  EXPECT_DOUBLE_EQ(norm(store.angular_velocity[0]), 0.0);  // no spin columns: no spin
}

TEST(CsvImport, ColumnsInAnyOrder) {
  Scene scene = make_scene();
  scene.sources.push_back(csv_source("reordered.csv"));
  ParticleStore store;
  create_particles(scene, store);
  ASSERT_EQ(store.size(), 1u);
  const Real4& p = store.position_radius[0];
  EXPECT_DOUBLE_EQ(p.x, 0.1);
  EXPECT_DOUBLE_EQ(p.y, 0.2);
  EXPECT_DOUBLE_EQ(p.z, 0.3);
  EXPECT_DOUBLE_EQ(p.w, 0.01);
  EXPECT_EQ(store.material[0], 1u);
  EXPECT_DOUBLE_EQ(store.velocity_inv_mass[0].z, -2.5);
  EXPECT_DOUBLE_EQ(store.velocity_inv_mass[0].x, 0.0);
}

// Importing `name` fails with an InputError at `line` and `key` whose message names the file.
void expect_csv_error(const std::string& name, int line, const std::string& key) {
  Scene scene = make_scene();
  scene.sources.push_back(csv_source(name));
  ParticleStore store;
  try {
    create_particles(scene, store);
    ADD_FAILURE() << name << ": expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.key(), key) << e.what();
    const std::string where = name + (line > 0 ? ":" + std::to_string(line) : "");
    EXPECT_NE(std::string(e.what()).find(where), std::string::npos) << e.what();
  }
}

TEST(CsvImport, BadFilesNameFileLineAndColumn) {
  expect_csv_error("no_such_file.csv", 0, "");
  expect_csv_error("empty.csv", 1, "");
  expect_csv_error("missing_r.csv", 1, "r");
  expect_csv_error("unknown_column.csv", 1, "colour");
  expect_csv_error("duplicate_column.csv", 1, "x");
  expect_csv_error("field_count.csv", 3, "");
  expect_csv_error("not_a_number.csv", 4, "y");
  expect_csv_error("radius_zero.csv", 3, "r");
  expect_csv_error("unknown_material.csv", 3, "material");
  expect_csv_error("material_index_out_of_range.csv", 3, "material");
  expect_csv_error("outside_domain.csv", 3, "z");
}

TEST(CsvImport, PartsOfTheRowsInOrderAreTheWholeFile) {
  Scene scene = make_scene();
  scene.sources.push_back(csv_source("rows_with_blanks.csv"));  // 7 rows among blank lines
  for (int parts = 1; parts <= 9; ++parts) {
    ParticleStore joined;
    for (int p = 0; p < parts; ++p)
      EXPECT_EQ(import_csv_part(scene, 0, FilePart{p, parts}, joined, 100), 7u);
    ASSERT_EQ(joined.size(), 7u) << parts << " parts";
    for (std::size_t k = 0; k < 7; ++k) {
      EXPECT_EQ(joined.id[k], 100 + k);
      EXPECT_DOUBLE_EQ(joined.position_radius[k].x, 0.1 * double(k + 1));
      EXPECT_DOUBLE_EQ(joined.velocity_inv_mass[k].z, double(k + 1));
    }
  }
}

TEST(CsvImport, APartReportsOnlyTheBadRowsItHolds) {
  Scene scene = make_scene();
  scene.sources.push_back(csv_source("not_a_number.csv"));  // row 1 of rows 0 and 1 is bad
  ParticleStore first;
  EXPECT_EQ(import_csv_part(scene, 0, FilePart{0, 2}, first, 0), 2u);
  EXPECT_EQ(first.size(), 1u);
  ParticleStore second;
  EXPECT_THROW(import_csv_part(scene, 0, FilePart{1, 2}, second, 0), InputError);
}

TEST(CsvImport, OutsideAlongAPeriodicAxisIsAccepted) {
  Scene scene = make_scene();
  scene.domain.periodic[2] = true;
  scene.sources.push_back(csv_source("outside_domain.csv"));
  ParticleStore store;
  create_particles(scene, store);
  EXPECT_EQ(store.size(), 2u);
}

}  // namespace
}  // namespace gpudem
