#pragma once
/// What bounds a scene's time step (docs/input.md, "Time step"): the contact duration, Rayleigh
/// time and stable step of its contact law, the step in which the fastest particle moves a
/// fraction of the smallest radius, and the deepest overlap an impact reaches.
#include <limits>
#include <vector>

#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"
#include "core/contact/NormalLaws.hpp"
#include "engine/MeshWallSetup.hpp"

namespace gpudem {

/// Time-step limits of a scene and its particles [s]; +infinity when there are no particles.
struct TimeStepLimits {
  /// t_c of one collision. hooke: π √(m*/k_n) for the two lightest particles. hertz:
  /// 2.87 (m*² / (R* E*² v))^{1/5} (Johnson 1985, ch. 11) at the impact speed v, smallest over
  /// the material pairs present (each material by its smallest particle) and the
  /// particle–wall pairs (R* = r, m* = m)
  double contact_duration = 0;
  /// T_R = π R √(ρ/G) / (0.1631 ν + 0.8766), G = E / (2(1 + ν)), smallest over the particles
  double rayleigh = 0;
  /// Largest explicit dt accepted: min(T_R, 2/ω), ω the angular frequency of the stiffest
  /// contact (velocity Verlet on an oscillator is stable for ω dt < 2). hooke: ω = √(k_n/m*);
  /// hertz: ω = √(S_max/m*) with the tangent stiffness at the peak overlap of an impact at v,
  /// S_max = 2 E* √(R* δ_max), δ_max = (15 m* v² / (16 E* √R*))^{2/5}
  double stable = 0;
  /// π/ω of the stiffest parallel bond (bond_frequency_squared), over the [[bond]] tables with
  /// the smallest particle of each of their materials; +infinity without bonds. `stable` is
  /// also at most 2/ω.
  double bond = std::numeric_limits<double>::infinity();
  /// v_max [m/s], the fastest a particle may close on another or on a wall (max_speed)
  double max_speed = 0;
  /// displacement_fraction × r_min / v_max: the step in which a particle at v_max moves that
  /// fraction of the smallest radius r_min
  double displacement = 0;
  double critical() const {
    const double contact = contact_duration < rayleigh ? contact_duration : rayleigh;
    return contact < bond ? contact : bond;
  }
  /// dt = "auto": dt_fraction × critical(), at most the displacement step.
  double automatic(double dt_fraction) const {
    const double step = dt_fraction * critical();
    return step < displacement ? step : displacement;
  }
};

/// Impact speed v of the Hertz limits and of peak_overlap [m/s]: simulation.impact_speed, or for
/// "auto" √(2 |g| H) plus the largest particle speed, H the extent of the domain along g; 1 m/s
/// when both terms are 0.
double impact_speed(const Scene& scene, const ParticleStore& particles);

/// v_max [m/s]: √(2 |g| H) plus the largest particle speed (as impact_speed "auto") plus the
/// fastest point of any mesh, |v| + |ω| ρ over its keyframes, ρ its farthest vertex from its
/// rotation centre, plus the fastest piston, √(2 |P + M g·n| L / M) with L the domain's extent
/// along its normal, plus the fastest velocity prescribed to a fixed material; 0 when all of
/// these are 0.
double max_speed(const Scene& scene, const ParticleStore& particles,
                 const std::vector<MeshWallSetup>& meshes);

/// The fastest point of any mesh over the run, |v| + |ω| ρ at its fastest keyframe, ρ its
/// farthest vertex from its rotation centre [m/s]; 0 without meshes.
double fastest_tool(const Scene& scene, const std::vector<MeshWallSetup>& meshes);

/// Limits for the particles present; `meshes` as the scene's (for v_max).
TimeStepLimits time_step_limits(const Scene& scene, const ParticleStore& particles,
                                const std::vector<MeshWallSetup>& meshes);

/// The overlap, as a fraction of the smaller radius of a contact, beyond which a run stops as
/// unstable, and a scene whose impacts would reach it is refused at start-up.
constexpr double kUnstableOverlapRatio = 0.5;

/// The deepest overlap of an undamped impact at speed v (Normal::peak_overlap), as a fraction of
/// the smaller radius of the contact: an upper bound, dashpots only make it shallower.
struct PeakOverlap {
  double ratio = 0;         ///< δ_max / r, r the smaller radius (the particle's against a wall)
  double speed = 0;         ///< v [m/s]
  double radius = 0;        ///< r of the deepest contact [m]
  MaterialId material = 0;  ///< of its particle of radius r
  MaterialId other = 0;     ///< of the other particle or the wall
  bool wall = false;        ///< the other is a wall
  double unstable_speed =
      0;  ///< the impact speed at which that contact reaches kUnstableOverlapRatio [m/s]
};

/// The speed of the impacts a scene surely has [m/s]: simulation.impact_speed, or for "auto" the
/// fastest particle plus the fastest mesh point (max_speed without the free fall, which a
/// settled bed never makes).
double launch_speed(const Scene& scene, const ParticleStore& particles,
                    const std::vector<MeshWallSetup>& meshes);

/// PeakOverlap at impact speed v over every two of `particles` (as setup_deciding_particles
/// selects them: of each material the smallest, and the largest, lightest and fastest of all)
/// and each of them with each wall material; ratio 0 without particles.
PeakOverlap peak_overlap(const Scene& scene, const ParticleStore& particles, double v);

/// E* and G* of two materials (HertzNormal, MindlinTangential) [Pa].
double pair_young_modulus(const Material& a, const Material& b);
double pair_shear_modulus(const Material& a, const Material& b);

/// The smallest radius in the store, or +inf.
double smallest_radius(const ParticleStore& particles);

/// Index of the smallest particle of each material; particles.size() for an absent material.
std::vector<std::size_t> smallest_particle_per_material(const Scene& scene,
                                                        const ParticleStore& particles);

}  // namespace gpudem
