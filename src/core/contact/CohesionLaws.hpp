#pragma once
/// Cohesion slot: an attractive normal force added to the contact (moist soil).
#include "core/ContactParams.hpp"
#include "core/contact/ContactPoint.hpp"

namespace gpudem {

struct NoCohesion {
  static constexpr const char* keyword = "none";
  static constexpr const char* material_keys = "";
  static constexpr bool needs_contact_area = false;
  template <class S>
  GPUDEM_HD static S force(const ContactPairParamsT<S>&, const ContactPointT<S>&) {
    return 0;
  }
};

/// Simplified JKR of LIGGGHTS `cohesion sjkr`: F_c = k_c · A with A = π a² the contact-circle
/// area and k_c the cohesion energy density [J/m³]; it pulls the pair together and does not
/// enter the Coulomb limit. Acts only while the particles overlap.
struct SjkrCohesion {
  static constexpr const char* keyword = "sjkr";
  static constexpr const char* material_keys = "cohesion_energy_density";
  static constexpr bool needs_contact_area = true;
  template <class S>
  GPUDEM_HD static S force(const ContactPairParamsT<S>& p, const ContactPointT<S>& c) {
    return p.cohesion_energy_density * S(3.14159265358979323846) * c.contact_radius_sq;
  }
};

}  // namespace gpudem
