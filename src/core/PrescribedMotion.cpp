#include "core/PrescribedMotion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gpudem {

namespace {

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// The linear interpolation of a and b at fraction s ∈ [0, 1].
Vec3 lerp(Vec3 a, Vec3 b, double s) { return a + s * (b - a); }

}  // namespace

PrescribedMotion::PrescribedMotion(Vec3 centre, std::vector<MotionKeyframe> keyframes)
    : centre_(centre), keyframes_(std::move(keyframes)) {
  if (!finite(centre_)) throw std::invalid_argument("the rotation centre must be finite");
  for (std::size_t k = 0; k < keyframes_.size(); ++k) {
    const MotionKeyframe& f = keyframes_[k];
    if (!std::isfinite(f.time) || !finite(f.velocity) || !finite(f.angular_velocity))
      throw std::invalid_argument("keyframe " + std::to_string(k + 1) + " is not finite");
    if (k > 0 && !(f.time > keyframes_[k - 1].time))
      throw std::invalid_argument("keyframe times must increase strictly (keyframe " +
                                  std::to_string(k + 1) + ")");
  }
}

Vec3 PrescribedMotion::value(double t, Vec3 MotionKeyframe::*field) const {
  if (keyframes_.empty() || t < keyframes_.front().time || t > keyframes_.back().time)
    return Vec3{};
  const auto after = std::upper_bound(keyframes_.begin(), keyframes_.end(), t,
                                      [](double x, const MotionKeyframe& f) { return x < f.time; });
  if (after == keyframes_.end()) return keyframes_.back().*field;
  const MotionKeyframe& b = *after;
  const MotionKeyframe& a = *(after - 1);
  return lerp(a.*field, b.*field, (t - a.time) / (b.time - a.time));
}

Vec3 PrescribedMotion::integral(double t0, double t1, Vec3 MotionKeyframe::*field) const {
  Vec3 sum;
  for (std::size_t k = 0; k + 1 < keyframes_.size(); ++k) {
    const MotionKeyframe& a = keyframes_[k];
    const MotionKeyframe& b = keyframes_[k + 1];
    const double lo = std::max(t0, a.time), hi = std::min(t1, b.time);
    if (!(hi > lo)) continue;
    const double span = b.time - a.time;
    const Vec3 at_lo = lerp(a.*field, b.*field, (lo - a.time) / span);
    const Vec3 at_hi = lerp(a.*field, b.*field, (hi - a.time) / span);
    sum += (0.5 * (hi - lo)) * (at_lo + at_hi);  // trapezoid: exact for a linear segment
  }
  return sum;
}

Vec3 PrescribedMotion::velocity(double t) const { return value(t, &MotionKeyframe::velocity); }

Vec3 PrescribedMotion::angular_velocity(double t) const {
  return value(t, &MotionKeyframe::angular_velocity);
}

Vec3 PrescribedMotion::displacement(double t0, double t1) const {
  return integral(t0, t1, &MotionKeyframe::velocity);
}

Vec3 PrescribedMotion::rotation_vector(double t0, double t1) const {
  return integral(t0, t1, &MotionKeyframe::angular_velocity);
}

Vec3 PrescribedMotion::centre(double t) const { return centre_ + displacement(0, t); }

RigidIncrement PrescribedMotion::increment(double t, double dt) const {
  RigidIncrement step;
  step.centre = centre(t);
  step.translation = displacement(t, t + dt);
  step.rotation = rotation_by_vector(rotation_vector(t, t + dt));
  return step;
}

}  // namespace gpudem
