#pragma once
/// The units in which the host's force sweep sums contact loads as integers (ExactSum.hpp).

namespace gpudem {

/// The units of a run's integer sums, powers of two, the same on every rank
/// (exact_units_for_grains), and their inverses. The defaults are those of grains of 0.1 N and
/// 1 mm and up.
struct ExactUnits {
  double force = 0x1p-44;      ///< [N]
  double torque = 0x1p-54;     ///< [N m]
  double per_force = 0x1p44;   ///< 1 / force, exact
  double per_torque = 0x1p54;  ///< 1 / torque, exact
};

/// The units of a run whose lightest grain weighs `lightest_weight` [N] under standard gravity
/// and whose smallest grain has radius `smallest_radius` [m] (both positive and finite):
/// u = 2^-40 of that weight, rounded down to a power of two, for forces, and u times the radius,
/// rounded down, for torques. The sums then resolve 10^-12 of the lightest grain's weight, and a
/// term of up to 2^50 u, a thousand of those weights or more, takes the one-word path.
ExactUnits exact_units_for_grains(double lightest_weight, double smallest_radius);

/// The units `force` [N] and `torque` [N m] (powers of two) and their inverses.
inline ExactUnits exact_units_of(double force, double torque) {
  return {force, torque, 1 / force, 1 / torque};
}

}  // namespace gpudem
