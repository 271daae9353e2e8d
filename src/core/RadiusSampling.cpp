#include "core/RadiusSampling.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/FreeCentre.hpp"

namespace gpudem {
namespace {

constexpr double pi = 3.14159265358979323846;
/// Redraws of a truncated normal are bounded by refusing bounds this improbable.
constexpr double min_truncated_normal_mass = 1e-6;

/// Standard normal deviate by the Box–Muller transform (Box & Muller 1958).
double standard_normal(std::mt19937_64& rng) {
  const double u1 = 1.0 - uniform01(rng);  // in (0, 1]: the logarithm stays finite
  const double u2 = uniform01(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * pi * u2);
}

/// Standard normal cumulative distribution Φ(x) = erfc(-x/√2)/2.
double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

/// Probability that normal(mean, stddev) falls in [min, max].
double truncated_normal_mass(const RadiusDistribution& d) {
  if (d.stddev <= 0) return d.min <= d.mean && d.mean <= d.max ? 1.0 : 0.0;
  return normal_cdf((d.max - d.mean) / d.stddev) - normal_cdf((d.min - d.mean) / d.stddev);
}

/// Weights of a discrete distribution; none given means equally likely values.
std::vector<double> discrete_weights(const RadiusDistribution& d) {
  std::vector<double> w = d.weights.empty() ? std::vector<double>(d.values.size(), 1.0) : d.weights;
  w.resize(d.values.size(), 0.0);
  return w;
}

/// Radii a discrete distribution can produce: the values of positive weight.
std::vector<double> discrete_support(const RadiusDistribution& d) {
  const std::vector<double> w = discrete_weights(d);
  std::vector<double> support;
  for (std::size_t k = 0; k < w.size(); ++k)
    if (w[k] > 0) support.push_back(d.values[k]);
  return support;
}

/// The positive weights, in the order of discrete_support().
std::vector<double> positive_weights(const RadiusDistribution& d) {
  std::vector<double> w = discrete_weights(d);
  w.erase(std::remove_if(w.begin(), w.end(), [](double x) { return !(x > 0); }), w.end());
  return w;
}

}  // namespace

std::string sampling_problem(const RadiusDistribution& d) {
  if (d.kind == RadiusDistributionKind::Discrete && discrete_support(d).empty())
    return "discrete distribution has no value of positive weight";
  if (d.kind == RadiusDistributionKind::TruncatedNormal &&
      !(truncated_normal_mass(d) >= min_truncated_normal_mass))
    return "[min, max] holds almost none of the normal(mean, stddev) distribution";
  return {};
}

std::vector<double> sample_radii(const RadiusDistribution& dist, std::size_t count,
                                 std::mt19937_64& rng) {
  const std::string problem = sampling_problem(dist);
  if (!problem.empty()) throw std::invalid_argument("sample_radii: " + problem);
  std::vector<double> radii(count);
  switch (dist.kind) {
    case RadiusDistributionKind::Uniform:
      for (double& r : radii) r = dist.mean - dist.spread + 2 * dist.spread * uniform01(rng);
      break;
    case RadiusDistributionKind::TruncatedNormal:
      for (double& r : radii) {
        do r = dist.mean + dist.stddev * standard_normal(rng);
        while (r < dist.min || r > dist.max);
      }
      break;
    case RadiusDistributionKind::Discrete: {
      const std::vector<double> support = discrete_support(dist);
      std::vector<double> cumulative = positive_weights(dist);
      std::partial_sum(cumulative.begin(), cumulative.end(), cumulative.begin());
      for (double& r : radii) {
        const double u = uniform01(rng) * cumulative.back();
        const auto k =
            std::upper_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin();
        r = support[std::min(static_cast<std::size_t>(k), support.size() - 1)];
      }
      break;
    }
  }
  return radii;
}

double min_radius(const RadiusDistribution& dist) {
  switch (dist.kind) {
    case RadiusDistributionKind::Uniform:
      return dist.mean - dist.spread;
    case RadiusDistributionKind::TruncatedNormal:
      return dist.min;
    case RadiusDistributionKind::Discrete: {
      const std::vector<double> s = discrete_support(dist);
      return s.empty() ? 0.0 : *std::min_element(s.begin(), s.end());
    }
  }
  return 0.0;
}

double max_radius(const RadiusDistribution& dist) {
  switch (dist.kind) {
    case RadiusDistributionKind::Uniform:
      return dist.mean + dist.spread;
    case RadiusDistributionKind::TruncatedNormal:
      return dist.max;
    case RadiusDistributionKind::Discrete: {
      const std::vector<double> s = discrete_support(dist);
      return s.empty() ? 0.0 : *std::max_element(s.begin(), s.end());
    }
  }
  return 0.0;
}

}  // namespace gpudem
