#pragma once
/// Outputs and history of a force evaluation whose results are thrown away (launch tuning).
#include <cstddef>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/DeviceArray.hpp"

namespace gpudem {

template <class Space, class S>
struct ForceScratchOf {
  ForceScratchOf(std::size_t owned, std::size_t pairs, std::size_t wall_slots, std::size_t mesh)
      : force(owned),
        torque(owned),
        overlap_ratio(owned),
        pair(pairs),
        wall(wall_slots),
        mesh(mesh) {}
  /// The bytes the constructor allocates.
  static std::size_t bytes(std::size_t owned, std::size_t pairs, std::size_t wall_slots,
                           std::size_t mesh) {
    return owned * (2 * sizeof(Vec3T<S>) + sizeof(Real)) + (pairs + wall_slots + mesh) * sizeof(S);
  }
  DeviceArray<Vec3T<S>, Space> force, torque;
  DeviceArray<Real, Space> overlap_ratio;
  DeviceArray<S, Space> pair, wall, mesh;  ///< history values
};

}  // namespace gpudem
