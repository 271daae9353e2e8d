#include "engine/ExactSum.hpp"

namespace gpudem {

namespace {
/// The largest power of two not above x (positive and finite).
double power_of_two_below(double x) {
  int exponent = 0;
  std::frexp(x, &exponent);  // x = m · 2^exponent, m in [0.5, 1)
  return std::ldexp(1.0, exponent - 1);
}
}  // namespace

ExactUnits exact_units_for_grains(double lightest_weight, double smallest_radius) {
  const double force = power_of_two_below(lightest_weight * 0x1p-40);
  const double torque = power_of_two_below(force * smallest_radius);
  return exact_units_of(force, torque);
}

ExactTerm3 exact_terms_in_units(double x, double y, double z) {
  ExactTerm3 t{{}, {0, 0, 0}, true, true};
  const double units[3] = {x, y, z};
  for (int k = 0; k < 3; ++k) {
    const double u = units[k];
    if (!(std::fabs(u) < exact_spill_limit)) {  // NaN: not representable either
      t.representable = false;
      return t;
    }
    // u − spill · 2^50 is exact (Sterbenz: spill · 2^50 is within a factor 2 of u, or spill is
    // 0), and below 2^49 in magnitude
    const double spill = std::rint(u * 0x1p-50);
    t.spill[k] = static_cast<std::uint64_t>(static_cast<std::int64_t>(spill));
    t.words.word[k] = static_cast<std::uint64_t>(std::llrint(u - spill * 0x1p50));
  }
  return t;
}

double exact_detail::spilled_component(std::uint64_t word, std::uint64_t spill, double unit) {
  __extension__ typedef __int128 Wide;  // GCC and Clang
  // two's complement (C++20 rule, what every compiler does); the integer is exact in 128 bits,
  // so its one rounding does not depend on how the terms split it into word and spill
  const Wide units = static_cast<Wide>(static_cast<std::int64_t>(word)) +
                     static_cast<Wide>(static_cast<std::int64_t>(spill)) * (Wide(1) << 50);
  return static_cast<double>(units) * unit;
}

}  // namespace gpudem
