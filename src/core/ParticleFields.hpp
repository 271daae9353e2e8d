#pragma once
/// The particle field table (docs/architecture.md, "Particle fields"): every per-particle field
/// is declared here once, with its name, its value type in each precision policy, where it
/// travels and what keeps it. Resizing, sorting, ghost and migration packing, start-up routing,
/// staging, checkpoints and the memory report loop over this table; adding a field is one
/// entry in ParticleFieldTable plus the code that uses its values.
#include <array>
#include <cstddef>
#include <cstring>
#include <type_traits>

#include "core/Config.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// What a particle field takes part in, as bits of a use set.
namespace field_use {
/// Ghosts hold it: sent in full with each ghost on a rebuild step.
inline constexpr unsigned ghost = 1u << 0;
/// Sent to the ghosts on every step (a contact evaluation reads it).
inline constexpr unsigned refresh = 1u << 1;
/// Sent to the ghosts on every step when the contact law reads particle spins.
inline constexpr unsigned spin_refresh = 1u << 2;
/// Survives a rebuild: sorted with its particle and migrating with it (the other fields are
/// recomputed after each rebuild).
inline constexpr unsigned persistent = 1u << 3;
/// Written to checkpoints and carried by the start-up routing of particle shares.
inline constexpr unsigned checkpoint = 1u << 4;
/// Every use.
inline constexpr unsigned any = ~0u;
}  // namespace field_use

/// A snapshot dataset taken from a field: `count` of its components from component `first`
/// on. "position" is in every snapshot; the others are those of kSnapshotFields
/// (core/OutputNames.hpp) that a run asks for.
struct SnapshotColumn {
  const char* name;
  int first;
  int count;
};

/// The fields of the table. `name` names the field's checkpoint dataset; `Value<P, S>` is its
/// value type in the engine, whose particle state is in scalar P and loads in the law's scalar
/// S; the host's ParticleStore holds `Value<Real, Real>` in the member that `of` names;
/// `memory_label` groups fields in the memory report; `snapshot` lists the snapshot datasets
/// taken from it.
namespace particle_field {

struct PositionRadius {
  static constexpr const char* name = "position_radius";  ///< x, y, z [m] and radius [m]
  static constexpr const char* memory_label = "position, radius";
  static constexpr unsigned use =
      field_use::ghost | field_use::refresh | field_use::persistent | field_use::checkpoint;
  static constexpr std::array<SnapshotColumn, 2> snapshot{{{"position", 0, 3}, {"radius", 3, 1}}};
  template <class P, class S>
  using Value = Vec4T<P>;
  template <class Store>
  static auto& of(Store& s) {
    return s.position_radius;
  }
};

struct VelocityInvMass {
  static constexpr const char* name = "velocity_inv_mass";  ///< vx, vy, vz [m/s], 1/m [1/kg]
  static constexpr const char* memory_label = "velocity, inverse mass";
  static constexpr unsigned use =
      field_use::ghost | field_use::refresh | field_use::persistent | field_use::checkpoint;
  static constexpr std::array<SnapshotColumn, 1> snapshot{{{"velocity", 0, 3}}};
  template <class P, class S>
  using Value = Vec4T<P>;
  template <class Store>
  static auto& of(Store& s) {
    return s.velocity_inv_mass;
  }
};

struct AngularVelocity {
  static constexpr const char* name = "angular_velocity";  ///< [rad/s]
  static constexpr const char* memory_label = "angular velocity";
  static constexpr unsigned use =
      field_use::ghost | field_use::spin_refresh | field_use::persistent | field_use::checkpoint;
  static constexpr std::array<SnapshotColumn, 1> snapshot{{{"angular_velocity", 0, 3}}};
  template <class P, class S>
  using Value = Vec3T<P>;
  template <class Store>
  static auto& of(Store& s) {
    return s.angular_velocity;
  }
};

struct Id {
  static constexpr const char* name = "id";  ///< global id, unique for the whole run
  static constexpr const char* memory_label = "id, material";
  static constexpr unsigned use = field_use::ghost | field_use::persistent | field_use::checkpoint;
  static constexpr std::array<SnapshotColumn, 1> snapshot{{{"id", 0, 1}}};
  template <class P, class S>
  using Value = ParticleId;
  template <class Store>
  static auto& of(Store& s) {
    return s.id;
  }
};

struct Material {
  static constexpr const char* name = "material";  ///< index into Scene::materials
  static constexpr const char* memory_label = "id, material";
  static constexpr unsigned use = field_use::ghost | field_use::persistent | field_use::checkpoint;
  static constexpr std::array<SnapshotColumn, 1> snapshot{{{"material", 0, 1}}};
  template <class P, class S>
  using Value = MaterialId;
  template <class Store>
  static auto& of(Store& s) {
    return s.material;
  }
};

struct Force {
  static constexpr const char* name = "force";  ///< total force of the last evaluation [N]
  static constexpr const char* memory_label = "force, torque";
  static constexpr unsigned use = field_use::checkpoint;
  static constexpr std::array<SnapshotColumn, 1> snapshot{{{"force", 0, 3}}};
  template <class P, class S>
  using Value = Vec3T<S>;
  template <class Store>
  static auto& of(Store& s) {
    return s.force;
  }
};

struct Torque {
  static constexpr const char* name = "torque";  ///< total torque of the last evaluation [N m]
  static constexpr const char* memory_label = "force, torque";
  static constexpr unsigned use = field_use::checkpoint;
  static constexpr std::array<SnapshotColumn, 0> snapshot{};
  template <class P, class S>
  using Value = Vec3T<S>;
  template <class Store>
  static auto& of(Store& s) {
    return s.torque;
  }
};

}  // namespace particle_field

/// One T per field F, named by the field: FieldTuple<Of, F...>::get<F>() is the value of type
/// `Of::type<F>`. An aggregate of its values, so a tuple of pointers is passed to kernels by
/// value.
template <class F, class T>
struct FieldSlot {
  T value;
};

template <class Of, class... F>
struct FieldTuple : FieldSlot<F, typename Of::template type<F>>... {
  template <class G>
  GPUDEM_HD typename Of::template type<G>& get() {
    return static_cast<FieldSlot<G, typename Of::template type<G>>&>(*this).value;
  }
  template <class G>
  GPUDEM_HD const typename Of::template type<G>& get() const {
    return static_cast<const FieldSlot<G, typename Of::template type<G>>&>(*this).value;
  }
};

/// A list of fields, visited in its order.
template <class... F>
struct FieldList {
  static constexpr std::size_t size = sizeof...(F);

  /// Calls fn(G{}) for each field G of the list whose uses meet `Use`, in list order.
  GPUDEM_HD_CALLS_ANY
  template <unsigned Use, class Fn>
  GPUDEM_HD static void for_each(Fn&& fn) {
    (visit_if<Use, F>(fn), ...);
  }

  /// A FieldTuple over every field of the list.
  template <class Of>
  using Tuple = FieldTuple<Of, F...>;

  /// Bytes of one row of the fields whose uses meet `Use`, values of scalars P and S packed
  /// back to back without padding (the wire format, WireRow).
  template <unsigned Use, class P, class S>
  static constexpr std::size_t row_bytes() {
    return ((F::use & Use ? sizeof(typename F::template Value<P, S>) : 0) + ... + 0);
  }

 private:
  GPUDEM_HD_CALLS_ANY
  template <unsigned Use, class G, class Fn>
  GPUDEM_HD static void visit_if(Fn& fn) {
    if constexpr ((G::use & Use) != 0) fn(G{});
  }
};

/// Every per-particle field, in the order rows are packed, checkpoints are written and the
/// memory report lists them.
using ParticleFieldTable =
    FieldList<particle_field::PositionRadius, particle_field::VelocityInvMass,
              particle_field::AngularVelocity, particle_field::Id, particle_field::Material,
              particle_field::Force, particle_field::Torque>;

/// Calls fn(F{}) for each field of the table whose uses meet `Use`.
GPUDEM_HD_CALLS_ANY
template <unsigned Use = field_use::any, class Fn>
GPUDEM_HD void for_each_particle_field(Fn&& fn) {
  ParticleFieldTable::for_each<Use>(fn);
}

/// The value type of field F in the engine's scalars P (state) and S (loads).
template <class F, class P, class S>
using FieldValue = typename F::template Value<P, S>;

/// Holders for FieldTuple: one pointer to the values of each field, in scalars P and S.
template <class P, class S>
struct PointerPerField {
  template <class F>
  using type = FieldValue<F, P, S>*;
};

/// Pointers to every field's values (in any memory space); passed to kernels by value.
template <class P, class S>
using ParticlePointers = ParticleFieldTable::Tuple<PointerPerField<P, S>>;

/// A value converted to another scalar, component by component (ids and indices unchanged).
template <class To, class From>
GPUDEM_HD To value_cast(const From& v) {
  if constexpr (std::is_same_v<To, From>)
    return v;
  else if constexpr (std::is_same_v<To, Vec4T<decltype(To{}.x)>>)
    return vec4_cast<decltype(To{}.x)>(v);
  else
    return vec_cast<decltype(To{}.x)>(v);
}

/// Scalar components of a field value, for per-component packing and I/O: a Vec4T has 4, a
/// Vec3T 3, anything else is one scalar.
template <class T>
struct ValueComponents {
  using Scalar = T;
  static constexpr int count = 1;
  GPUDEM_HD static T get(const T& v, int) { return v; }
  GPUDEM_HD static void set(T& v, int, T s) { v = s; }
};
template <class S>
struct ValueComponents<Vec3T<S>> {
  using Scalar = S;
  static constexpr int count = 3;
  GPUDEM_HD static S get(const Vec3T<S>& v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }
  GPUDEM_HD static void set(Vec3T<S>& v, int k, S s) { (k == 0 ? v.x : k == 1 ? v.y : v.z) = s; }
};
template <class S>
struct ValueComponents<Vec4T<S>> {
  using Scalar = S;
  static constexpr int count = 4;
  GPUDEM_HD static S get(const Vec4T<S>& v, int k) {
    return k == 0 ? v.x : k == 1 ? v.y : k == 2 ? v.z : v.w;
  }
  GPUDEM_HD static void set(Vec4T<S>& v, int k, S s) {
    (k == 0 ? v.x : k == 1 ? v.y : k == 2 ? v.z : v.w) = s;
  }
};

static_assert(sizeof(Vec4T<float>) == 4 * sizeof(float) &&
                  sizeof(Vec4T<double>) == 4 * sizeof(double) &&
                  sizeof(Vec3T<float>) == 3 * sizeof(float) &&
                  sizeof(Vec3T<double>) == 3 * sizeof(double),
              "field values are packed and stored as their components, without padding");

/// One particle's row of the fields whose uses meet `Use`, as bytes: each field's value in
/// table order, back to back (row_bytes per row). The one format in which particles travel:
/// ghost records, migration and start-up routing.
template <unsigned Use, class P, class S>
struct WireRow {
  static constexpr std::size_t bytes = ParticleFieldTable::row_bytes<Use, P, S>();

  /// Writes row i of `from` to `out`; a field whose pointer is null is written as zeros.
  GPUDEM_HD static void write(const ParticlePointers<P, S>& from, std::size_t i, char* out) {
    std::size_t at = 0;
    for_each_particle_field<Use>([&](auto field) {
      using F = decltype(field);
      const FieldValue<F, P, S>* values = from.template get<F>();
      if (values)
        std::memcpy(out + at, values + i, sizeof(FieldValue<F, P, S>));
      else
        std::memset(out + at, 0, sizeof(FieldValue<F, P, S>));
      at += sizeof(FieldValue<F, P, S>);
    });
  }

  /// Reads a row from `in` into row i of `to`.
  GPUDEM_HD static void read(const char* in, const ParticlePointers<P, S>& to, std::size_t i) {
    std::size_t at = 0;
    for_each_particle_field<Use>([&](auto field) {
      using F = decltype(field);
      std::memcpy(&to.template get<F>()[i], in + at, sizeof(FieldValue<F, P, S>));
      at += sizeof(FieldValue<F, P, S>);
    });
  }
};

}  // namespace gpudem
