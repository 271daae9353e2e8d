#pragma once
/// Turns a validated scene and its particles into the engine's plain setup: the contact pair
/// table, walls, Verlet skin and time step (docs/input.md, "Time step").
#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"
#include "engine/StepEngine.hpp"

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
  double critical() const { return contact_duration < rayleigh ? contact_duration : rayleigh; }
};

/// Impact speed v of the Hertz limits [m/s]: simulation.impact_speed, or for "auto"
/// √(2 |g| H) plus the largest particle speed, H the extent of the domain along g; 1 m/s when
/// both terms are 0.
double impact_speed(const Scene& scene, const ParticleStore& particles);

/// Limits for the particles present.
TimeStepLimits time_step_limits(const Scene& scene, const ParticleStore& particles);

/// The engine setup: contact model, pair table (material_count² entries, row-major,
/// symmetric), walls, skin and dt (dt_fraction × critical step when the scene says "auto",
/// end_time when there are no particles). Throws InputError naming simulation.dt when an
/// explicit dt exceeds the stable limit and simulation.allow_unstable_dt is false, and naming
/// mesh[i].file when a mesh spans 2 h_k >= L_k - 2 (r_max + 2 skin) along a periodic axis k
/// (h_k: half its extent, or for a mesh that ever rotates the largest distance from its
/// bounding-box centre to a vertex), and as require_meshes_meet_the_domain (MeshReach.hpp)
/// when a mesh never meets the domain or is smaller than the smallest particle.
EngineSetup make_engine_setup(const Scene& scene, const ParticleStore& particles);

/// The particles of `particles` that decide time_step_limits and make_engine_setup: of each
/// material the first of smallest radius, and the first of largest radius, of largest inverse
/// mass and of highest speed, in store order. Both functions give the same for them as for all
/// the particles; and the selections of consecutive shares of a store, concatenated in order,
/// give the same as the store's, so each rank selects from its share and the ranks gather.
ParticleStore setup_deciding_particles(const Scene& scene, const ParticleStore& particles);

}  // namespace gpudem
