// Triangle-mesh walls in the engine: a mesh plane acts exactly like the analytic plane wall
// (also where a sphere rolls across the edge two triangles share), and a moving mesh plate
// hits a sphere as rigid-body impact theory says, with the momentum the mesh force carries.
#include <gtest/gtest.h>

#include <cmath>

#include "core/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A square of side 2·half in the plane through `centre` spanned by u and v (normal u × v),
/// as two triangles sharing the diagonal from corner (−u −v) to corner (+u +v).
TriangleMesh square(Vec3 centre, Vec3 u, Vec3 v, double half) {
  const Vec3 a = centre - half * u - half * v, b = centre + half * u - half * v,
             c = centre + half * u + half * v, d = centre - half * u + half * v;
  return build_mesh({{a, b, c}, {a, c, d}});
}

/// Hertz–Mindlin with restitution e, friction μ and constant-torque rolling resistance μ_r.
Scene hertz_scene(double e, double mu, double mu_r) {
  Scene s = basic_scene({-1, -1, -1}, {1, 1, 1}, 0, e, mu);
  s.contact.model = {NormalLaw::Hertz, DampingLaw::Restitution, TangentialLaw::Mindlin,
                     mu_r > 0 ? RollingLaw::ConstantTorque : RollingLaw::None, CohesionLaw::None};
  s.materials[0].rolling_friction = mu_r;
  s.simulation.dt_auto = false;
  s.simulation.dt = 2e-6;
  return s;
}

ParticleStore one_sphere(const Scene& s, Vec3 x, Vec3 v, double r) {
  ParticleStore p;
  p.add(0, x, r, 0, v, 1.0 / sphere_mass(s.materials[0].density, r));
  return p;
}

class MeshWall : public BackendTest {
 protected:
  /// Positions of one sphere after each of `blocks` × `steps` steps.
  std::vector<Vec3> trajectory(const EngineSetup& setup, ParticleStore p, int blocks, int steps) {
    auto engine = make_engine(setup);
    engine->set_particles(p);
    std::vector<Vec3> path;
    for (int b = 0; b < blocks; ++b) {
      for (int n = 0; n < steps; ++n) engine->step();
      engine->get_particles(p);
      path.push_back(xyz(p.position_radius[0]));
    }
    return path;
  }
};

/// A sphere on a plane tilted by 20° about x, once as a plane wall and once as a mesh of two
/// triangles whose shared diagonal lies across its path: it rolls (μ_r = 0) or is held by
/// rolling resistance (μ_r = 0.5 > tan 20°), and both walls give the same trajectory.
TEST_P(MeshWall, TiltedMeshPlaneMatchesAnalyticPlane) {
  const double tilt = 20 * kPi / 180, r = 0.01;
  const Vec3 down_slope{0, -std::cos(tilt), -std::sin(tilt)};
  const Vec3 normal{0, -std::sin(tilt), std::cos(tilt)};
  for (double mu_r : {0.0, 0.5}) {
    SCOPED_TRACE("rolling friction " + std::to_string(mu_r));
    Scene plane = hertz_scene(0.3, 0.8, mu_r);
    WallSettings wall;
    wall.normal = normal;
    plane.walls.push_back(wall);
    // 0.07 m up the slope from the diagonal, which runs through the origin at 45° in the plane
    const Vec3 start = (r - 2e-6) * normal + Vec3{0.03, 0, 0} - 0.1 * down_slope;
    const ParticleStore p = one_sphere(plane, start, {}, r);
    Scene meshed = hertz_scene(0.3, 0.8, mu_r);
    const EngineSetup plane_setup = make_engine_setup(plane, p);
    EngineSetup mesh_setup = make_engine_setup(meshed, p);
    MeshWallSetup tool;
    tool.mesh = square({0, 0, 0}, {1, 0, 0}, {0, std::cos(tilt), std::sin(tilt)}, 0.5);
    mesh_setup.meshes.push_back(tool);
    const auto expected = trajectory(plane_setup, p, 40, 5000);  // 0.4 s
    const auto got = trajectory(mesh_setup, p, 40, 5000);
    double worst = 0;
    for (std::size_t k = 0; k < got.size(); ++k) worst = std::max(worst, norm(got[k] - expected[k]));
    const double travelled = norm(expected.back() - start);
    RecordProperty("largest_position_difference_m_mu_r_" + std::to_string(int(mu_r * 10)),
                   significant(worst));
    EXPECT_LT(worst, 1e-9);
    if (mu_r == 0) {
      EXPECT_GT(dot(expected.back() - start, down_slope), 0.1);  // rolled over the diagonal
    } else {
      EXPECT_LT(travelled, 1e-3);  // held
    }
  }
}

/// A mesh plate moving at V = 0.5 m/s hits a sphere at rest (no gravity, no friction): the
/// sphere leaves at (1 + e) V (impact on an infinite mass), and the impulse the mesh force
/// carries equals the sphere's momentum.
TEST_P(MeshWall, MovingPlatePushesSphere) {
  const double V = 0.5, r = 0.01;
  for (double e : {0.5, 1.0}) {
    SCOPED_TRACE("restitution " + std::to_string(e));
    Scene s = hertz_scene(e, 0.0, 0);
    s.simulation.gravity = {0, 0, 0};
    s.contact.model.tangential = TangentialLaw::None;
    ParticleStore p = one_sphere(s, {0.05, 0, 0}, {}, r);
    const double m = 1 / p.velocity_inv_mass[0].w;
    EngineSetup setup = make_engine_setup(s, p);
    MeshWallSetup plate;
    plate.mesh = square({0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 0.2);  // the plane x = 0, normal +x
    plate.motion = PrescribedMotion({0, 0, 0}, {{0, {V, 0, 0}, {}}, {1, {V, 0, 0}, {}}});
    setup.meshes.push_back(plate);
    auto engine = make_engine(setup);
    engine->set_particles(p);
    double impulse = 0;
    for (int n = 0; n < 60000; ++n) {  // 0.12 s: contact at t ≈ 0.08 s, over by 0.1 s
      engine->step();
      if (n % 10 == 9) impulse -= 10 * s.simulation.dt * engine->diagnostics().mesh_force[0].x;
    }
    engine->get_particles(p);
    const double v = p.velocity_inv_mass[0].x;
    RecordProperty("rebound_speed_e_" + std::to_string(int(e * 10)), significant(v));
    EXPECT_NEAR(v, (1 + e) * V, 0.01 * (1 + e) * V);
    EXPECT_NEAR(impulse, m * v, 0.01 * m * v);
    EXPECT_GT(p.position_radius[0].x, V * 0.12 + r);  // ahead of the plate
  }
}

GPUDEM_INSTANTIATE_BACKENDS(MeshWall);

}  // namespace
}  // namespace gpudem::test
