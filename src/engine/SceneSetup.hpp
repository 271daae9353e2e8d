#pragma once
/// Turns a validated scene and its particles into the engine's plain setup: the contact pair
/// table, walls, Verlet skin and time step (docs/input.md, "Time step").
#include "core/ParticleStore.hpp"
#include "core/Scene.hpp"
#include "engine/StepEngine.hpp"
#include "engine/TimeStepLimits.hpp"

namespace gpudem {

/// Start-up warnings of a scene's step: impacts past the instability limit that
/// simulation.allow_unstable_dt lets run, and an explicit dt that lets a particle at v_max move
/// more than simulation.displacement_fraction of the smallest radius in one step.
std::vector<std::string> time_step_warnings(const Scene& scene, const ParticleStore& particles,
                                            const EngineSetup& setup);

/// The contact constants of materials a and b (one entry of EngineSetup::pair_params): elastic
/// constants from the materials, the other values from their [[pair]] entry where it gives one,
/// else the mixing rule.
ContactPairParams pair_params(const Scene& scene, MaterialId a, MaterialId b);

/// The units of the host sweep's integer sums (exact_units_for_grains): of the lightest particle
/// (by its mass, or for a fixed one its material's density and radius) and the smallest.
ExactUnits exact_units(const Scene& scene, const ParticleStore& particles);

/// The engine setup: contact model, pair table (material_count² entries, row-major,
/// symmetric), walls and pistons, skin and dt (TimeStepLimits::automatic when the scene says
/// "auto"; dt_fraction × TimeStepLimits::critical, the base step, when it says "adaptive";
/// end_time when there are no particles). Throws InputError naming wall[i].mass for a piston
/// lighter than a close-packed layer of the heaviest particles against it. Throws InputError naming
/// simulation.dt when an explicit dt exceeds the stable limit and simulation.allow_unstable_dt is
/// false; naming the key that stiffens the contact (contact.stiffness, or material[i].young of its
/// softer material) when an impact's peak overlap (peak_overlap) would pass kUnstableOverlapRatio
/// and simulation.allow_unstable_dt is false; naming mesh[i].file when a mesh spans 2 h_k >= L_k -
/// 2 (r_max + 2 skin) along a periodic axis k (h_k: half its extent, or for a mesh that ever
/// rotates the largest distance from its bounding-box centre to a vertex), and as
/// require_meshes_meet_the_domain (MeshReach.hpp) when a mesh never meets the domain or is smaller
/// than the smallest particle; naming neighbor.skin when JKR adhesion holds a contact further
/// past touch than the skin (the neighbour list would lose it). Its integer sums' units are
/// exact_units'.
EngineSetup make_engine_setup(const Scene& scene, const ParticleStore& particles);

/// The particles of `particles` that decide time_step_limits and make_engine_setup: of each
/// material the first of smallest radius, and the first of largest radius, of largest and of
/// smallest inverse mass and of highest speed, in store order. Both functions give the same for
/// them as for all the particles; and the selections of consecutive shares of a store, concatenated
/// in order, give the same as the store's, so each rank selects from its share and the ranks
/// gather. So does exact_units.
ParticleStore setup_deciding_particles(const Scene& scene, const ParticleStore& particles);

}  // namespace gpudem
