#pragma once
/// Cohesion slot: the pull that holds a contact together (moist soil). Each choice gives
///   adhere         the contact as the elastic slots see it (the same, or JKR's Hertz-equivalent)
///                  and its pull F_c ≥ 0 there, subtracted from the normal force;
///   friction_load  the load that sets the Coulomb and rolling limits;
///   energy         the energy its pull stores (the part not in Normal::energy);
///   pull_off_gap   how far past touch a formed contact holds (0: it parts at touch).
/// A choice with a gap keeps one history value per contact, 1 once the contact has formed.
#include "core/ContactParams.hpp"
#include "core/contact/ContactPoint.hpp"
#include "core/contact/JkrRelation.hpp"

namespace gpudem {

/// A contact as the elastic slots see it, and the cohesion's pull there.
template <class S>
struct Adhesion {
  ContactPointT<S> point;
  S pull = 0;  ///< F_c ≥ 0, towards the partner [N]
};

/// The members shared by the choices that act only while the particles overlap.
struct TouchingCohesion {
  static constexpr int history_size = 0;
  static constexpr bool evaluates_in_lanes = true;  ///< ContactLaw::evaluates_in_lanes
  static constexpr bool needs_effective_radius = false;
  template <class S>
  GPUDEM_HD static S friction_load(const ContactPairParamsT<S>&, const ContactPointT<S>&,
                                   S elastic_force, S) {
    return elastic_force;
  }
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>&, const ContactPointT<S>&) {
    return 0;
  }
  template <class S>
  GPUDEM_HD static S pull_off_gap(const ContactPairParamsT<S>&, S) {
    return 0;
  }
};

struct NoCohesion : TouchingCohesion {
  static constexpr const char* keyword = "none";
  static constexpr const char* material_keys = "";
  static constexpr bool needs_contact_area = false;
  template <class S>
  GPUDEM_HD static Adhesion<S> adhere(const ContactPairParamsT<S>&, const ContactPointT<S>& c) {
    return {c, S(0)};
  }
};

/// Simplified JKR of LIGGGHTS `cohesion sjkr`: F_c = k_c · A with A = π a² the contact-circle
/// area and k_c the cohesion energy density [J/m³]; it pulls the pair together and does not
/// enter the Coulomb limit. Acts only while the particles overlap; its energy is not counted.
struct SjkrCohesion : TouchingCohesion {
  static constexpr const char* keyword = "sjkr";
  static constexpr const char* material_keys = "cohesion_energy_density";
  static constexpr bool needs_contact_area = true;
  template <class S>
  GPUDEM_HD static Adhesion<S> adhere(const ContactPairParamsT<S>& p, const ContactPointT<S>& c) {
    return {c, p.cohesion_energy_density * S(3.14159265358979323846) * c.contact_radius_sq};
  }
};

/// JKR adhesion (Johnson, Kendall & Roberts 1971; JkrRelation.hpp) on the Hertz law: at overlap
/// δ the contact radius a follows the JKR relation, the elastic slots see the Hertz contact of
/// that radius (overlap a²/R*: force 4E* a³/(3R*), stiffness 2E* a, Mindlin 8G* a) and the pull
/// √(8π γ E* a³) is subtracted, so the normal force is JKR's. A contact forms at touch and holds
/// in tension until δ_c = −3 a_c²/R*, where it parts; the largest pull on the way is the
/// pull-off force 3/2 π γ R*. The Coulomb and rolling limits scale with F_JKR + 2·(3/2 π γ R*),
/// which stays positive while the contact holds (Thornton & Yin 1991, Powder Technol. 65:153).
/// γ: the pair's work of adhesion [J/m²].
struct JkrCohesion {
  static constexpr const char* keyword = "jkr";
  static constexpr const char* material_keys = "surface_energy";
  static constexpr bool needs_contact_area = false;
  static constexpr bool needs_effective_radius = true;
  static constexpr int history_size = 1;
  static constexpr bool evaluates_in_lanes = false;  ///< its solve branches
  /// The formed flag is the same seen from either end.
  static constexpr int negated_values = 0;
  /// With x = √(a/R*) and k = π γ/(8E* R*) (jkr_relative_radius): overlap a²/R* = R* x⁴ and
  /// pull √(8π γ E* a³) = 8 E* R*² √k x³, no root beyond those of the solve.
  template <class S>
  GPUDEM_HD static Adhesion<S> adhere(const ContactPairParamsT<S>& p, const ContactPointT<S>& c) {
    Adhesion<S> out{c, S(0)};
    const S r = c.effective_radius;
    if (!(p.surface_energy > 0)) {
      out.point.overlap = c.overlap > 0 ? c.overlap : S(0);
      return out;
    }
    const S k = jkr_adhesion_number(p.surface_energy, p.effective_young, r);
    const S x2 = jkr_relative_radius(k, c.overlap / r);  // x² = a/R*
    const S x = square_root(x2);
    out.point.overlap = r * x2 * x2;
    out.pull = S(8) * p.effective_young * r * r * square_root(k) * x2 * x;
    return out;
  }
  template <class S>
  GPUDEM_HD static S friction_load(const ContactPairParamsT<S>& p, const ContactPointT<S>& e,
                                   S elastic_force, S pull) {
    return elastic_force - pull +
           S(3) * S(3.14159265358979323846) * p.surface_energy * e.effective_radius;
  }
  template <class S>
  GPUDEM_HD static S energy(const ContactPairParamsT<S>& p, const ContactPointT<S>& e) {
    return jkr_adhesive_energy(p.surface_energy, p.effective_young, e.effective_radius,
                               square_root(e.effective_radius * e.overlap));
  }
  template <class S>
  GPUDEM_HD static S pull_off_gap(const ContactPairParamsT<S>& p, S effective_radius) {
    return p.surface_energy > 0
               ? jkr_pull_off_gap(p.surface_energy, p.effective_young, effective_radius)
               : S(0);
  }
};

}  // namespace gpudem
