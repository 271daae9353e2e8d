#pragma once
/// Host-side particle state as a structure of arrays (docs/architecture.md, "Memory").
/// Owned particles occupy [0, size()); ghosts are appended after them once decomposition exists.
/// Device copies of these arrays live in the step engine; transfers are explicit.
#include <cstddef>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

struct ParticleStore {
  std::vector<Real4> position_radius;    ///< x, y, z [m] and radius [m]
  std::vector<Real4> velocity_inv_mass;  ///< vx, vy, vz [m/s] and 1/mass [1/kg]
  std::vector<Vec3> angular_velocity;    ///< [rad/s]
  std::vector<Vec3> force;               ///< total force of the last evaluation [N]
  std::vector<Vec3> torque;              ///< total torque of the last evaluation [N m]
  std::vector<ParticleId> id;            ///< global id, unique for the whole run
  std::vector<MaterialId> material;      ///< index into Scene::materials

  std::size_t size() const { return id.size(); }

  /// Appends one particle with zero spin, force and torque; the caller gives 1/mass.
  void add(ParticleId global_id, Vec3 position, Real radius, MaterialId mat, Vec3 velocity,
           Real inv_mass) {
    position_radius.push_back({position.x, position.y, position.z, radius});
    velocity_inv_mass.push_back({velocity.x, velocity.y, velocity.z, inv_mass});
    angular_velocity.push_back({});
    force.push_back({});
    torque.push_back({});
    id.push_back(global_id);
    material.push_back(mat);
  }

  /// Room for `rows` rows in every array.
  void reserve(std::size_t rows) {
    position_radius.reserve(rows);
    velocity_inv_mass.reserve(rows);
    angular_velocity.reserve(rows);
    force.reserve(rows);
    torque.reserve(rows);
    id.reserve(rows);
    material.reserve(rows);
  }

  /// Appends every row of `more`.
  void append(const ParticleStore& more) {
    const auto extend = [](auto& to, const auto& from) {
      to.insert(to.end(), from.begin(), from.end());
    };
    extend(position_radius, more.position_radius);
    extend(velocity_inv_mass, more.velocity_inv_mass);
    extend(angular_velocity, more.angular_velocity);
    extend(force, more.force);
    extend(torque, more.torque);
    extend(id, more.id);
    extend(material, more.material);
  }

  void clear() { *this = ParticleStore{}; }
};

/// Sphere volume from its radius: V = 4/3 π r^3.
inline double sphere_volume(double radius) {
  return 4.0 / 3.0 * 3.14159265358979323846 * radius * radius * radius;
}

/// Sphere mass from density and radius: m = 4/3 π r^3 ρ.
inline Real sphere_mass(Real density, Real radius) {
  return Real(4.0 / 3.0 * 3.14159265358979323846) * radius * radius * radius * density;
}

/// Moment of inertia of a solid sphere, I = 2/5 m r², from its radius and inverse mass.
GPUDEM_HD inline Real sphere_inertia(Real radius, Real inv_mass) {
  return Real(0.4) * radius * radius / inv_mass;
}

}  // namespace gpudem
