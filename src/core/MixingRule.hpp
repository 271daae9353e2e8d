#pragma once
/// How the values of two materials combine into the value of their contact pair.
#include <string>
#include <vector>

namespace gpudem {

enum class MixingRule { Mean, Min, Max, Harmonic };

/// Scene-file names of the rules, in enum order.
inline const std::vector<std::string>& mixing_rule_names() {
  static const std::vector<std::string> names{"mean", "min", "max", "harmonic"};
  return names;
}

/// Pair value of the material values a and b: the arithmetic mean (a + b)/2, the smaller, the
/// larger, or the harmonic mean 2ab/(a + b) (0 when a + b = 0).
inline double mix(MixingRule rule, double a, double b) {
  switch (rule) {
    case MixingRule::Min:
      return a < b ? a : b;
    case MixingRule::Max:
      return a > b ? a : b;
    case MixingRule::Harmonic:
      return a + b == 0 ? 0.0 : 2 * a * b / (a + b);
    case MixingRule::Mean:
      break;
  }
  return 0.5 * (a + b);
}

}  // namespace gpudem
