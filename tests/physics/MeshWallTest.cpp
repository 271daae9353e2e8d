// Triangle-mesh walls in the engine: a mesh plane acts exactly like the analytic plane wall
// (also where a sphere rolls across the edge two triangles share), and a moving mesh plate
// hits a sphere as rigid-body impact theory says, with the momentum the mesh force carries.
// The per-triangle loads of the snapshot output: a sphere pressed into one triangle of a mesh
// plane loads that triangle alone with the Hooke force k δ, at the pressure k δ / A, and on a
// moving plane under many spheres each triangle carries what its spheres push on it, adding up
// to the mesh force of the diagnostics. In a box periodic along x, a plate sticking out through
// the face x = 1 holds the spheres on the other side of the face as their periodic images: a
// sphere rolling across the face follows the analytic plane, and one at rest there stays at the
// equilibrium overlap, with the torque of its weight about the mesh's centre taken at its image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "engine/SceneSetup.hpp"
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
    for (std::size_t k = 0; k < got.size(); ++k)
      worst = std::max(worst, norm(got[k] - expected[k]));
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

/// Hooke contact of stiffness k without damping (e = 1) or friction, and the given gravity.
Scene elastic_scene(double k, Vec3 gravity) {
  Scene s = basic_scene({-1, -1, -1}, {1, 1, 1}, k, 1.0, 0.0);
  s.simulation.gravity = gravity;
  s.simulation.dt_auto = false;
  s.simulation.dt = 1e-5;
  return s;
}

/// |a − b| / |b|.
double relative_difference(Vec3 a, Vec3 b) { return norm(a - b) / norm(b); }

/// The plane z = 0 as a square of side 1 (half width 0.5), two triangles of area 0.5 each:
/// triangle 0 covers y < x, triangle 1 covers y > x; both have normal +z.
constexpr double kHalf = 0.5;
constexpr double kTriangleArea = 2 * kHalf * kHalf;

MeshWallSetup floor_plate() {
  MeshWallSetup plate;
  plate.mesh = square({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, kHalf);
  return plate;
}

/// A sphere at rest pressed δ into one triangle of the plane: that triangle carries the whole
/// load (0, 0, −k δ), the other none, they add up to the mesh force of the diagnostics, the
/// surface is the plate's, and the pressure on the loaded triangle (normal +z, towards the
/// sphere) is k δ / A.
TEST_P(MeshWall, PressedSphereLoadsOnlyItsTriangleWithThePressureOfTheHookeForce) {
  const double k = 1e4, r = 0.01, delta = 1e-4;
  const Vec3 over_triangle[2] = {{0.2, -0.2, r - delta}, {-0.25, 0.15, r - delta}};
  for (int loaded = 0; loaded < 2; ++loaded) {
    SCOPED_TRACE("sphere over triangle " + std::to_string(loaded));
    const Scene s = elastic_scene(k, {0, 0, -9.81});
    const ParticleStore p = one_sphere(s, over_triangle[loaded], {}, r);
    EngineSetup setup = make_engine_setup(s, p);
    setup.meshes.push_back(floor_plate());
    auto engine = make_engine(setup);
    engine->set_particles(p);
    const Vec3 mesh_force = engine->diagnostics().mesh_force[0];
    const std::vector<MeshSurface> surfaces = engine->mesh_surfaces();
    ASSERT_EQ(surfaces.size(), 1u);
    const MeshSurface& plate = surfaces[0];
    ASSERT_EQ(plate.vertices.size(), 4u);
    for (std::size_t v = 0; v < 4; ++v)  // a plate standing still keeps its vertices exactly
      EXPECT_EQ(norm(plate.vertices[v] - setup.meshes[0].mesh.vertices[v]), 0.0) << v;
    EXPECT_EQ(plate.triangles, setup.meshes[0].mesh.triangles);
    ASSERT_EQ(plate.triangle_force.size(), 2u);
    const Vec3 hooke{0, 0, -k * delta};  // the particle pushes the plate down
    EXPECT_LT(relative_difference(mesh_force, hooke), 1e-12);
    const Vec3 sum = plate.triangle_force[0] + plate.triangle_force[1];
    RecordProperty("triangle_sum_vs_mesh_force_" + std::to_string(loaded),
                   significant(relative_difference(sum, mesh_force)));
    EXPECT_LT(relative_difference(sum, mesh_force), 1e-12);
    EXPECT_LT(relative_difference(plate.triangle_force[loaded], mesh_force), 1e-12);
    EXPECT_EQ(norm(plate.triangle_force[1 - loaded]), 0.0);
    const std::vector<double> pressure = triangle_pressures(plate);
    const double expected = k * delta / kTriangleArea;  // −F · ẑ / A
    RecordProperty("pressure_Pa_" + std::to_string(loaded), significant(pressure[loaded]));
    EXPECT_NEAR(pressure[loaded], expected, 1e-12 * std::abs(expected));
    EXPECT_EQ(pressure[1 - loaded], 0.0);
  }
}

/// Spheres resting on both triangles of a plane that moves at V (overlaps near the static
/// m g / k, so they stay in contact while the plate lifts them): after some steps the vertices
/// are the plate's moved by V t, and each triangle carries the sum over the spheres above it of
/// m g − F (without damping or friction, the only other force on a sphere is the plate's,
/// −load); the triangles add up to the mesh force of the diagnostics.
TEST_P(MeshWall, EachTriangleCarriesTheLoadOfTheSpheresOnIt) {
  const double k = 1e4, r = 0.01;
  const Vec3 g{0, 0, -9.81}, V{0.02, -0.01, 0.005};
  const Scene s = elastic_scene(k, g);
  ParticleStore p;
  const double m = sphere_mass(s.materials[0].density, r);
  const Vec3 places[] = {{0.2, -0.2, 0}, {0.3, 0.0, 0},  {0.0, -0.35, 0},
                         {-0.2, 0.2, 0}, {-0.3, 0.1, 0}, {0.05, 0.3, 0}};
  for (std::size_t i = 0; i < std::size(places); ++i)
    p.add(i, places[i] + Vec3{0, 0, r - (1 + 0.05 * i) * m * norm(g) / k}, r, 0, {}, 1 / m);
  EngineSetup setup = make_engine_setup(s, p);
  MeshWallSetup plate = floor_plate();
  plate.motion = PrescribedMotion({0, 0, 0}, {{0, V, {}}, {1, V, {}}});
  setup.meshes.push_back(plate);
  auto engine = make_engine(setup);
  engine->set_particles(p);
  const int steps = 300;
  for (int n = 0; n < steps; ++n) engine->step();
  engine->get_particles(p);
  const MeshSurface surface = engine->mesh_surfaces()[0];
  const Vec3 moved = steps * s.simulation.dt * V;
  for (std::size_t v = 0; v < surface.vertices.size(); ++v)
    EXPECT_LT(norm(surface.vertices[v] - (plate.mesh.vertices[v] + moved)), 1e-15) << v;
  Vec3 expected[2];
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 x = xyz(p.position_radius[i]);
    ASSERT_GT(std::abs(x.x - x.y), 2 * r) << "sphere " << i << " reached the diagonal";
    expected[x.y > x.x ? 1 : 0] += m * g - p.force[i];
  }
  double worst = 0;
  for (int t = 0; t < 2; ++t) {
    ASSERT_GT(norm(expected[t]), m * norm(g)) << "too few spheres press on triangle " << t;
    worst = std::max(worst, relative_difference(surface.triangle_force[t], expected[t]));
  }
  RecordProperty("triangle_force_vs_sphere_loads", significant(worst));
  EXPECT_LT(worst, 1e-12);
  const Vec3 mesh_force = engine->diagnostics().mesh_force[0];
  const Vec3 sum = surface.triangle_force[0] + surface.triangle_force[1];
  RecordProperty("triangle_sum_vs_mesh_force", significant(relative_difference(sum, mesh_force)));
  EXPECT_LT(relative_difference(sum, mesh_force), 1e-12);
}

/// The plate of the periodic tests: the plane z = 0 over x ∈ [0.7, 1.3], y ∈ [−0.3, 0.3] (two
/// triangles whose diagonal runs from (0.7, −0.3) to (1.3, 0.3)). In the box periodic along x
/// with L = 1, its part beyond x = 1 stands for x ∈ [0, 0.3].
MeshWallSetup plate_across_the_face() {
  MeshWallSetup plate;
  plate.mesh = square({1.0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0.3);
  return plate;
}

/// `s` in the box [0, 1) × [−0.5, 0.5] × [−0.5, 0.5], periodic along x.
Scene periodic_in_x(Scene s) {
  s.domain.min = {0, -0.5, -0.5};
  s.domain.max = {1, 0.5, 0.5};
  s.domain.periodic = {true, false, false};
  return s;
}

/// A sphere starting at x = 0.9 with v_x = 0.5 m/s slides, then rolls (Hertz–Mindlin, μ = 0.5)
/// on the plate across the face x = 1, and on on its part beyond the face, which holds it as
/// its image nearest the plate: its trajectory (positions compared modulo L) is that of the
/// same sphere on the analytic plane z = 0.
TEST_P(MeshWall, SphereRollingAcrossAPeriodicFaceFollowsTheAnalyticPlane) {
  const double r = 0.01;
  Scene plane = periodic_in_x(hertz_scene(0.3, 0.5, 0));
  add_floor(plane);
  const ParticleStore p = one_sphere(plane, {0.9, 0, r - 2e-6}, {0.5, 0, 0}, r);
  const EngineSetup plane_setup = make_engine_setup(plane, p);
  EngineSetup mesh_setup = make_engine_setup(periodic_in_x(hertz_scene(0.3, 0.5, 0)), p);
  mesh_setup.meshes.push_back(plate_across_the_face());
  const auto expected = trajectory(plane_setup, p, 40, 5000);  // 0.4 s
  const auto got = trajectory(mesh_setup, p, 40, 5000);
  double worst = 0;
  for (std::size_t k = 0; k < got.size(); ++k)
    worst = std::max(worst, norm(plane_setup.box.minimum_image(got[k] - expected[k])));
  RecordProperty("largest_position_difference_m", significant(worst));
  // Only rounding separates the two: the image shifts x by exactly L (1 m), and the closest
  // point on the mesh carries rounding of ~1e-16 m, as does the tilted plane above (1.3e-13 m
  // over 0.4 s), which 1e-12 m bounds with room.
  EXPECT_LT(worst, 1e-12);
  const double end_x = expected.back().x;                    // wrapped into [0, 1)
  EXPECT_GT(end_x, 0.02);                                    // past the face by more than a radius
  EXPECT_LT(end_x, 0.3 - 2 * r);                             // still on the plate
  for (const Vec3& x : expected) EXPECT_NEAR(x.z, r, 1e-4);  // on the plane all the way
}

/// A sphere at rest at x = 0.1, over the plate's part beyond the face (Hooke k, no damping),
/// started at the equilibrium overlap δ = m g / k, stays there; the diagnostics give the plate
/// the force (0, 0, −m g) and, about the mesh's centre (the origin), the torque of that force
/// at the image contact point (1.1, 0, ·): (0, 1.1 m g, 0).
TEST_P(MeshWall, SphereAtRestBeyondAPeriodicFaceStaysAtTheEquilibriumOverlap) {
  const double k = 1e4, r = 0.01, g = 9.81;
  const Scene s = periodic_in_x(elastic_scene(k, {0, 0, -g}));
  const double m = sphere_mass(s.materials[0].density, r);
  const double delta = m * g / k;
  ParticleStore p = one_sphere(s, {0.1, 0, r - delta}, {}, r);
  EngineSetup setup = make_engine_setup(s, p);
  setup.meshes.push_back(plate_across_the_face());
  auto engine = make_engine(setup);
  engine->set_particles(p);
  double worst = 0;
  for (int block = 0; block < 10; ++block) {  // 0.1 s: a free fall would take 4.9 cm
    for (int n = 0; n < 1000; ++n) engine->step();
    engine->get_particles(p);
    worst = std::max(worst, std::abs((r - p.position_radius[0].z) - delta));
  }
  RecordProperty("largest_overlap_error_m", significant(worst));
  // The force balance k δ = m g holds to the rounding of z (ulp(0.01 m) = 1.7e-18 m); 1e-15 m
  // is several hundred times that.
  EXPECT_LT(worst, 1e-15);
  const Diagnostics d = engine->diagnostics();
  const Vec3 weight{0, 0, -m * g}, torque{0, 1.1 * m * g, 0};
  RecordProperty("mesh_force_relative_error",
                 significant(relative_difference(d.mesh_force[0], weight)));
  RecordProperty("mesh_torque_relative_error",
                 significant(relative_difference(d.mesh_torque[0], torque)));
  // δ = r − z carries the rounding of z: ulp(0.01 m) / δ ≈ 2e-13 relative.
  EXPECT_LT(relative_difference(d.mesh_force[0], weight), 1e-12);
  EXPECT_LT(relative_difference(d.mesh_torque[0], torque), 1e-12);
}

GPUDEM_INSTANTIATE_BACKENDS(MeshWall);

}  // namespace
}  // namespace gpudem::test
