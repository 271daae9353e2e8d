#pragma once
/// The engine's per-particle arrays, one per field of ParticleFieldTable (core/ParticleFields.hpp),
/// in the engine's memory space and scalars, with the operations the table drives: resizing,
/// sorting, host copies of rows and the memory report. Owned particles come first; the fields
/// that ghosts hold continue with the ghosts.
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "core/ParticleFields.hpp"
#include "core/ParticleStore.hpp"
#include "engine/ArrayKernels.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/Permute.hpp"
#include "engine/StepEngine.hpp"

namespace gpudem {

/// Holders for FieldTuple: one array of each field's values in memory Space.
template <class Space, class P, class S>
struct ArrayPerField {
  template <class F>
  using type = DeviceArray<FieldValue<F, P, S>, Space>;
};

/// Holders for FieldTuple: one host vector of each field's values.
template <class P, class S>
struct VectorPerField {
  template <class F>
  using type = std::vector<FieldValue<F, P, S>>;
};

/// Host vectors of every field (those a use leaves out stay empty).
template <class P, class S>
using ParticleVectors = ParticleFieldTable::Tuple<VectorPerField<P, S>>;

/// Pointers to the first values of every field of `v` (to be read only, when `v` is const).
template <class P, class S>
ParticlePointers<P, S> pointers_of(const ParticleVectors<P, S>& v) {
  ParticlePointers<P, S> out;
  for_each_particle_field([&](auto field) {
    using F = decltype(field);
    out.template get<F>() = const_cast<FieldValue<F, P, S>*>(v.template get<F>().data());
  });
  return out;
}

/// The engine's array of each particle field in memory Space, state in scalar P, loads in S.
template <class Space, class P, class S>
class ParticleColumns : public ParticleFieldTable::Tuple<ArrayPerField<Space, P, S>> {
 public:
  /// Pointers to every array, for kernels (to be read only, when the columns are const).
  ParticlePointers<P, S> pointers() const {
    ParticlePointers<P, S> out;
    for_each_particle_field([&](auto field) {
      using F = decltype(field);
      out.template get<F>() = const_cast<FieldValue<F, P, S>*>(this->template get<F>().data());
    });
    return out;
  }

  /// Sizes the arrays of the fields ghosts hold (owned particles, then ghosts) to `rows`.
  void resize_ghost_held(std::size_t rows) {
    for_each_particle_field<field_use::ghost>(
        [&](auto field) { this->template get<decltype(field)>().resize(rows); });
  }

  /// Sizes the arrays of the fields only owned particles hold to `owned` rows.
  void resize_owned_only(std::size_t owned) {
    for_each_particle_field([&](auto field) {
      using F = decltype(field);
      if constexpr ((F::use & field_use::ghost) == 0) this->template get<F>().resize(owned);
    });
  }

  /// Applies the permutation `order` (row k takes row order[k]) to the first n rows of the
  /// fields that survive a rebuild; the others keep n rows of no meaning until recomputed.
  void permute_persistent(const std::uint32_t* order, std::size_t n) {
    for_each_particle_field<field_use::persistent>([&](auto field) {
      using F = decltype(field);
      DeviceArray<FieldValue<F, P, S>, Space> out(n);
      permute(Space{}, order, this->template get<F>().data(), out.data(), n);
      this->template get<F>().swap(out);
    });
  }

  /// Host copies of rows [first, first + count) of the fields whose uses meet `Use`.
  template <unsigned Use>
  ParticleVectors<P, S> download_rows(std::size_t first, std::size_t count) const {
    ParticleVectors<P, S> out;
    for_each_particle_field<Use>([&](auto field) {
      using F = decltype(field);
      out.template get<F>() = download_values<Space>(this->template get<F>().data() + first, count);
    });
    return out;
  }

  /// Writes the rows of `rows` (fields whose uses meet `Use`) from row `first` on.
  template <unsigned Use>
  void upload_rows(const ParticleVectors<P, S>& rows, std::size_t first) {
    for_each_particle_field<Use>([&](auto field) {
      using F = decltype(field);
      upload_values<Space>(rows.template get<F>(), this->template get<F>().data() + first);
    });
  }

  /// Uploads the fields of `p` whose uses meet `Use` as rows [0, p.size()), rounded to the
  /// engine's scalars.
  template <unsigned Use>
  void upload_store(const ParticleStore& p) {
    for_each_particle_field<Use>([&](auto field) {
      using F = decltype(field);
      using Value = FieldValue<F, P, S>;
      const auto& host = F::of(p);
      if constexpr (std::is_same_v<Value, FieldValue<F, Real, Real>>) {
        this->template get<F>().upload(host);
      } else {
        std::vector<Value> rounded(host.size());
        for (std::size_t k = 0; k < host.size(); ++k) rounded[k] = value_cast<Value>(host[k]);
        this->template get<F>().upload(rounded);
      }
    });
  }

  /// Bytes held, per memory label, in table order (fields that share a label summed).
  std::vector<MemoryUse> memory_use() const {
    std::vector<MemoryUse> out;
    for_each_particle_field([&](auto field) {
      using F = decltype(field);
      const std::size_t bytes = this->template get<F>().bytes();
      if (!out.empty() && std::string_view(out.back().name) == F::memory_label)
        out.back().bytes += bytes;
      else
        out.push_back({F::memory_label, bytes});
    });
    return out;
  }
};

/// `out` holds rows [0, n) of `rows` (every field), converted to Real.
template <class P, class S>
void fill_particle_store(const ParticlePointers<P, S>& rows, std::size_t n, ParticleStore& out) {
  for_each_particle_field([&](auto field) {
    using F = decltype(field);
    auto& to = F::of(out);
    const FieldValue<F, P, S>* from = rows.template get<F>();
    to.resize(n);
    for (std::size_t k = 0; k < n; ++k) to[k] = value_cast<FieldValue<F, Real, Real>>(from[k]);
  });
}

}  // namespace gpudem
