// A portal frame of bonded spheres: two columns of 21 spheres on fixed feet and a beam of 31
// spheres joining their tops (rigid corners: the corner sphere is bonded to both), loaded by the
// spheres' weights and brought to rest by drag. Its nodes must rest where a plane frame of
// Euler–Bernoulli beam elements between the same nodes puts them under the same point loads (the
// direct stiffness method, solved here): the beam's midspan deflection and the corners'
// displacements within 2 %, and the frame symmetric. The load is light (g = 0.01 m/s²) so that
// the frame stays linear: under full gravity the beam's sag of L/330 shortens its chord by
// ∫ w'²/2 dx and pulls the corners in by 4.7 times the linear sway (7.8e-7 against 1.7e-7 m),
// which the linear method cannot see and the bonds, turning with the bond, do.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/SceneSetup.hpp"
#include "support/Backends.hpp"
#include "support/Format.hpp"
#include "support/SceneBuilder.hpp"

namespace gpudem::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kColumn = 20, kSpan = 30;  // elements per column and in the beam
constexpr double kRadius = 1e-3, kDensity = 1000, kYoung = 1e7, kGravity = 0.01;
constexpr ContactModel kElasticHertz{NormalLaw::Hertz, DampingLaw::None, TangentialLaw::None,
                                     RollingLaw::None, CohesionLaw::None};

double spacing() { return 2 * kRadius; }
double sphere_weight() { return sphere_mass(kDensity, kRadius) * kGravity; }

/// The frame's nodes in the x–z plane: the left column bottom to top (node 0 its foot), the
/// beam's inner nodes left to right, the right column top to bottom (the last node its foot).
std::vector<Vec3> frame_nodes() {
  std::vector<Vec3> nodes;
  const double height = kColumn * spacing(), span = kSpan * spacing();
  for (int k = 0; k <= kColumn; ++k) nodes.push_back({0, 0, k * spacing()});
  for (int k = 1; k < kSpan; ++k) nodes.push_back({k * spacing(), 0, height});
  for (int k = kColumn; k >= 0; --k) nodes.push_back({span, 0, k * spacing()});
  return nodes;
}

/// Node indices: the left corner, the midspan node, the right corner.
int left_corner() { return kColumn; }
int midspan() { return kColumn + kSpan / 2; }
int right_corner() { return kColumn + kSpan; }

/// The static displacements (x, z per node) of the plane frame of Euler–Bernoulli elements
/// between consecutive nodes (EA, EI of the bond's section), feet clamped, a weight at every
/// other node: K u = f by Gaussian elimination, three degrees of freedom per node (u_x, u_z, θ).
std::vector<Vec3> frame_displacements(const std::vector<Vec3>& nodes) {
  const int n = static_cast<int>(nodes.size()), dofs = 3 * n;
  const double area = kPi * kRadius * kRadius, inertia = 0.25 * kPi * std::pow(kRadius, 4);
  std::vector<double> k(dofs * dofs, 0.0), f(dofs, 0.0);
  for (int e = 0; e + 1 < n; ++e) {
    const Vec3 d = nodes[e + 1] - nodes[e];
    const double l = norm(d), c = d.x / l, s = d.z / l;
    const double a = kYoung * area / l, b = 12 * kYoung * inertia / (l * l * l);
    const double m = 6 * kYoung * inertia / (l * l), q = 4 * kYoung * inertia / l;
    // Local stiffness (axial, transverse, rotation at each end) and the rotation to x–z.
    const double local[6][6] = {{a, 0, 0, -a, 0, 0},     {0, b, m, 0, -b, m},
                                {0, m, q, 0, -m, q / 2}, {-a, 0, 0, a, 0, 0},
                                {0, -b, -m, 0, b, -m},   {0, m, q / 2, 0, -m, q}};
    const double turn[6][6] = {{c, s, 0, 0, 0, 0}, {-s, c, 0, 0, 0, 0}, {0, 0, 1, 0, 0, 0},
                               {0, 0, 0, c, s, 0}, {0, 0, 0, -s, c, 0}, {0, 0, 0, 0, 0, 1}};
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        double sum = 0;
        for (int p = 0; p < 6; ++p)
          for (int r = 0; r < 6; ++r) sum += turn[p][i] * local[p][r] * turn[r][j];
        k[(3 * e + i) * dofs + 3 * e + j] += sum;
      }
  }
  for (int i = 1; i + 1 < n; ++i) f[3 * i + 1] = -sphere_weight();
  for (const int foot : {0, n - 1})  // clamped: u = 0 by a unit row
    for (int v = 0; v < 3; ++v) {
      const int r = 3 * foot + v;
      for (int j = 0; j < dofs; ++j) k[r * dofs + j] = k[j * dofs + r] = 0;
      k[r * dofs + r] = 1;
      f[r] = 0;
    }
  for (int p = 0; p < dofs; ++p)  // elimination without pivoting: K is positive definite
    for (int r = p + 1; r < dofs; ++r) {
      const double factor = k[r * dofs + p] / k[p * dofs + p];
      if (factor == 0) continue;
      for (int j = p; j < dofs; ++j) k[r * dofs + j] -= factor * k[p * dofs + j];
      f[r] -= factor * f[p];
    }
  std::vector<double> u(dofs);
  for (int r = dofs - 1; r >= 0; --r) {
    double sum = f[r];
    for (int j = r + 1; j < dofs; ++j) sum -= k[r * dofs + j] * u[j];
    u[r] = sum / k[r * dofs + r];
  }
  std::vector<Vec3> displacement;
  for (int i = 0; i < n; ++i) displacement.push_back({u[3 * i], 0, u[3 * i + 1]});
  return displacement;
}

/// Material 0 the frame's spheres (with drag), material 1 the fixed feet.
Scene frame_scene() {
  Scene s = basic_scene({-0.02, -0.02, -0.02}, {0.08, 0.02, 0.06}, 0, 1, 0);
  s.materials[0].density = kDensity;
  s.materials[0].young = kYoung;
  s.materials[0].drag = 500;
  Material foot = s.materials[0];
  foot.name = "foot";
  foot.fixed = true;
  s.materials.push_back(foot);
  s.contact.model = kElasticHertz;
  for (const MaterialId other : {0u, 1u}) {
    BondSettings bond;
    bond.a = 0;
    bond.b = other;
    bond.gap = 1e-5;
    bond.young = kYoung;
    bond.poisson = 0.25;
    s.bonds.push_back(bond);
  }
  s.neighbor.skin = 5e-4;
  s.simulation.gravity = {0, 0, -kGravity};
  s.simulation.dt_auto = false;
  s.simulation.dt = 2e-6;
  return s;
}

class BondedFrame : public BackendTest {};

TEST_P(BondedFrame, RestsWhereTheStiffnessMethodPutsItsNodes) {
  const std::vector<Vec3> nodes = frame_nodes();
  const int n = static_cast<int>(nodes.size());
  ParticleStore p;
  const double inv_mass = 1 / sphere_mass(kDensity, kRadius);
  for (int i = 0; i < n; ++i)
    p.add(i, nodes[i], kRadius, (i == 0 || i == n - 1) ? 1 : 0, {0, 0, 0}, inv_mass);
  const Scene scene = frame_scene();
  auto engine = make_engine(make_engine_setup(scene, p));
  engine->set_particles(p);
  engine->create_bonds();
  ASSERT_EQ(engine->diagnostics().bond_count, std::uint64_t(n - 1));
  for (int step = 0; step < 50000; ++step) engine->step();
  engine->get_particles(p);
  std::vector<Vec3> moved(n);
  for (std::size_t i = 0; i < p.size(); ++i)
    moved[p.id[i]] = xyz(p.position_radius[i]) - nodes[p.id[i]];
  const std::vector<Vec3> expected = frame_displacements(nodes);
  const double sag = -moved[midspan()].z, expected_sag = -expected[midspan()].z;
  RecordProperty("midspan_deflection", significant(sag));
  RecordProperty("midspan_deflection_expected", significant(expected_sag));
  RecordProperty("corner_sway", significant(moved[left_corner()].x));
  RecordProperty("corner_sway_expected", significant(expected[left_corner()].x));
  EXPECT_NEAR(sag, expected_sag, 0.02 * expected_sag);
  for (const int corner : {left_corner(), right_corner()}) {
    EXPECT_NEAR(moved[corner].x, expected[corner].x, 0.02 * std::abs(expected[corner].x));
    EXPECT_NEAR(moved[corner].z, expected[corner].z, 0.02 * std::abs(expected[corner].z));
  }
  EXPECT_NEAR(moved[left_corner()].x, -moved[right_corner()].x,
              1e-3 * std::abs(moved[left_corner()].x));
  EXPECT_EQ(engine->diagnostics().broken_bond_count, 0u);
}

GPUDEM_INSTANTIATE_BACKENDS(BondedFrame);

}  // namespace
}  // namespace gpudem::test
