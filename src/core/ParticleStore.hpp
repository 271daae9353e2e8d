#pragma once
/// Host-side particle state as a structure of arrays (docs/architecture.md, "Memory").
/// Owned particles occupy [0, size()); ghosts are appended after them once decomposition exists.
/// Device copies of these arrays live in the step engine; transfers are explicit.
#include <cstddef>
#include <type_traits>
#include <vector>

#include "core/Config.hpp"
#include "core/ParticleFields.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// The fields of ParticleFieldTable (ParticleFields.hpp) in Real, each a member named by its
/// table entry.
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
    for_each_particle_field([&](auto field) { field.of(*this).emplace_back(); });
    position_radius.back() = {position.x, position.y, position.z, radius};
    velocity_inv_mass.back() = {velocity.x, velocity.y, velocity.z, inv_mass};
    id.back() = global_id;
    material.back() = mat;
  }

  /// Room for `rows` rows in every array.
  void reserve(std::size_t rows) {
    for_each_particle_field([&](auto field) { field.of(*this).reserve(rows); });
  }

  /// Appends every row of `more`.
  void append(const ParticleStore& more) {
    for_each_particle_field([&](auto field) {
      auto& to = field.of(*this);
      const auto& from = field.of(more);
      to.insert(to.end(), from.begin(), from.end());
    });
  }

  /// Appends row i of `from`; a field `from` lacks (the forces of a bed) is appended as zero.
  void append_row(const ParticleStore& from, std::size_t i) {
    for_each_particle_field([&](auto field) {
      const auto& values = field.of(from);
      using Value = typename std::decay_t<decltype(values)>::value_type;
      field.of(*this).push_back(values.size() == from.size() ? values[i] : Value{});
    });
  }

  void clear() { *this = ParticleStore{}; }
};

/// Pointers to the values of each field of `p`, to be read: null for a field that does not
/// hold one value per particle (which WireRow then writes as zeros).
inline ParticlePointers<Real, Real> row_pointers(const ParticleStore& p) {
  ParticlePointers<Real, Real> out;
  for_each_particle_field([&](auto field) {
    using F = decltype(field);
    const auto& values = F::of(p);
    out.template get<F>() =
        values.size() == p.size() ? const_cast<FieldValue<F, Real, Real>*>(values.data()) : nullptr;
  });
  return out;
}

/// Pointers to the values of each field of `p`, to be written.
inline ParticlePointers<Real, Real> row_pointers(ParticleStore& p) {
  ParticlePointers<Real, Real> out;
  for_each_particle_field(
      [&](auto field) { out.template get<decltype(field)>() = field.of(p).data(); });
  return out;
}

/// Sizes every field of `p` to `rows` rows, new rows zero.
inline void resize_rows(ParticleStore& p, std::size_t rows) {
  for_each_particle_field([&](auto field) { field.of(p).resize(rows); });
}

static_assert(sizeof(ParticleStore) == ParticleFieldTable::size * sizeof(std::vector<char>),
              "ParticleStore holds one vector per field of ParticleFieldTable, and nothing else");

/// Sphere volume from its radius: V = 4/3 π r^3.
inline double sphere_volume(double radius) {
  return 4.0 / 3.0 * 3.14159265358979323846 * radius * radius * radius;
}

/// Sphere mass from density and radius: m = 4/3 π r^3 ρ.
inline Real sphere_mass(Real density, Real radius) {
  return Real(4.0 / 3.0 * 3.14159265358979323846) * radius * radius * radius * density;
}

/// Moment of inertia of a solid sphere, I = 2/5 m r², from its radius and inverse mass.
template <class R>
GPUDEM_HD R sphere_inertia(R radius, R inv_mass) {
  return Real(0.4) * radius * radius / inv_mass;
}

}  // namespace gpudem
