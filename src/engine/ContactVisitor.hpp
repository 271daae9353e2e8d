#pragma once
/// Walks every contact of one particle — neighbours from the Verlet list, plane walls, then
/// mesh walls — and hands each touching one to a visitor (`visit(sample)`), and each listed
/// partner that is not touching to `visit.separated(slot)` (`separated_from_wall`,
/// `separated_from_mesh`). Forces, energies and counters are all
/// visitors, so the contact geometry lives in one place. The sweep loads only what the
/// contact law's capability flags ask for (spins, inertias, history).
#include <cstdint>
#include <type_traits>

#include "core/Config.hpp"
#include "core/ContactParams.hpp"
#include "core/ParticleStore.hpp"
#include "core/Vec3.hpp"
#include "core/contact/ContactLaw.hpp"
#include "core/contact/ParallelBond.hpp"
#include "engine/MeshWalls.hpp"
#include "engine/PeriodicBox.hpp"
#include "engine/PlaneWall.hpp"
#include "engine/WallReach.hpp"

namespace gpudem {

/// Read-only particle arrays a contact evaluation needs (pointers into one memory space), held
/// in the engine's state scalar P and read in Real. angular_velocity may be null for a law
/// that does not need spin.
template <class P>
struct ParticleView {
  const Vec4T<P>* position_radius;
  const Vec4T<P>* velocity_inv_mass;
  const Vec3T<P>* angular_velocity;
  const MaterialId* material;

  GPUDEM_HD Real4 position(std::size_t i) const { return vec4_cast<Real>(position_radius[i]); }
  GPUDEM_HD Real4 velocity(std::size_t i) const { return vec4_cast<Real>(velocity_inv_mass[i]); }
  GPUDEM_HD Vec3 spin(std::size_t i) const { return vec_cast<Real>(angular_velocity[i]); }
};

/// The state scalar of a particle view chosen at run time, double or float: the force computes
/// of a float law serve both the mixed policy (state in double) and the float policy (state in
/// float), so each float law is compiled once per backend, not once per policy.
struct EitherScalar {};

/// The particle arrays of a state held in double or in float, read in Real as ParticleView<P>
/// reads them; the branch on `is_float` is the same for every particle of a launch.
template <>
struct ParticleView<EitherScalar> {
  ParticleView<double> in_double;  ///< the arrays when the state is held in double
  ParticleView<float> in_float;    ///< the arrays when it is held in float
  bool is_float;
  const MaterialId* material;

  GPUDEM_HD Real4 position(std::size_t i) const {
    return is_float ? in_float.position(i) : in_double.position(i);
  }
  GPUDEM_HD Real4 velocity(std::size_t i) const {
    return is_float ? in_float.velocity(i) : in_double.velocity(i);
  }
  GPUDEM_HD Vec3 spin(std::size_t i) const {
    return is_float ? in_float.spin(i) : in_double.spin(i);
  }
};

/// The state scalar of the particle views a law of scalar S reads: Real for a double law (the
/// double policy), either for a float law (the mixed and float policies).
template <class S>
using ContactViewScalar = std::conditional_t<std::is_same_v<S, float>, EitherScalar, Real>;

/// A particle system's view as the force computes of law scalar S read it.
template <class S, class P>
ParticleView<ContactViewScalar<S>> contact_view(const ParticleView<P>& v) {
  if constexpr (std::is_same_v<ContactViewScalar<S>, P>) {
    return v;
  } else {
    ParticleView<EitherScalar> either{};
    either.is_float = std::is_same_v<P, float>;
    if constexpr (std::is_same_v<P, float>)
      either.in_float = v;
    else
      either.in_double = v;
    either.material = v.material;
    return either;
  }
}

/// The view without its spins, for a law that does not read them.
template <class P>
ParticleView<P> without_spin(ParticleView<P> v) {
  if constexpr (std::is_same_v<P, EitherScalar>) {
    v.in_double.angular_velocity = nullptr;
    v.in_float.angular_velocity = nullptr;
  } else {
    v.angular_velocity = nullptr;
  }
  return v;
}

/// Everything besides particles that a contact sweep needs; the history arrays hold
/// Law::history_size values per contact and are null for a law without history.
template <class Law>
struct ContactScene {
  const std::uint32_t* neighbor_offsets;    ///< CSR offsets, n + 1
  const std::uint32_t* neighbor_index;      ///< full neighbour list
  const typename Law::Params* pair_params;  ///< material_count² entries
  std::uint32_t material_count;
  const PlaneWall* walls;
  std::uint32_t wall_count;
  PeriodicBox box;
  /// Per owned particle, the plane walls it may touch before the next list build (WallReach.hpp);
  /// null without walls.
  const std::uint32_t* wall_reach;
  const typename Law::State* pair_history;  ///< per neighbour-list entry
  const typename Law::State* wall_history;  ///< per (particle, wall): slot i·wall_count + w
  MeshView mesh;
  const typename Law::State* mesh_history;  ///< per mesh candidate-list entry
  /// Per neighbour-list entry, bond_value::width values: a pair whose rest length is not 0 is
  /// bonded and has no contact (BondSet.hpp); null without bonds.
  const typename Law::Scalar* bond_records = nullptr;

  GPUDEM_HD bool bonded(std::uint32_t entry) const {
    return bond_records &&
           bond_records[std::size_t(entry) * bond_value::width + bond_value::rest_length] != 0;
  }
};

/// Base for visitors that ignore partners out of contact.
struct IgnoreSeparated {
  GPUDEM_HD void separated(std::uint32_t) {}
  GPUDEM_HD void separated_from_wall(std::uint32_t) {}
  GPUDEM_HD void separated_from_mesh(std::uint32_t) {}
};

/// One touching contact as seen from particle i, its geometry formed in Real from the
/// particle state.
template <class Law>
struct ContactSample {
  ContactPoint point;
  Real arm;         ///< lever arm on i: r_i − δ/2, along point.normal [m]
  Real min_radius;  ///< smaller radius of the pair (r_i for walls) [m]
  const typename Law::Params* params;
  std::int32_t wall;          ///< plane wall index, or −1
  std::int32_t mesh = -1;     ///< mesh index, or −1
  std::uint32_t slot;         ///< index of this contact's history (pair, wall or mesh array)
  typename Law::State state;  ///< history stored at the end of the last step
};

/// The law's force and rolling torque on i for contact c, in the law's scalar; advances
/// `history` by dt (dt = 0: reads the stored state).
template <class Law>
GPUDEM_HD typename Law::Force evaluate_contact(const ContactSample<Law>& c,
                                               typename Law::Scalar* history, Real dt) {
  using S = typename Law::Scalar;
  return Law::evaluate(*c.params, point_cast<S>(c.point), history, static_cast<S>(dt));
}

/// Elastic energy stored in contact c [J].
template <class Law>
GPUDEM_HD Real contact_energy(const ContactSample<Law>& c) {
  using S = typename Law::Scalar;
  return Law::energy(*c.params, point_cast<S>(c.point), c.state.value);
}

/// Moment of inertia about the contact point, I + m r², of a sphere (for I_r).
template <class R>
GPUDEM_HD R inertia_about_contact(R radius, R inv_mass) {
  return sphere_inertia(radius, inv_mass) + radius * radius / inv_mass;
}

/// The pair contact of particle i (centre and radius xi, velocity and inverse mass vi, spin wi)
/// with a partner at d = x_j − x_i, |d|² = dist2 > 0: the normal, the overlap, i's lever arm
/// r_i − δ/2 and the fields the law's flags ask for. R is Real, or Lanes of Real for several
/// contacts at once (core/Lanes.hpp), each lane the same bits as one contact in Real.
template <class Law, class R>
GPUDEM_HD void describe_pair(ContactPointT<R>& k, R& arm, Vec3T<R> d, R dist2, Vec4T<R> xi,
                             Vec4T<R> vi, Vec3T<R> wi, Vec4T<R> xj, Vec4T<R> vj, Vec3T<R> wj) {
  const R dist = square_root(dist2);
  k.normal = (Real(1) / dist) * d;
  k.overlap = xi.w + xj.w - dist;
  arm = xi.w - Real(0.5) * k.overlap;
  const R arm_j = xj.w - Real(0.5) * k.overlap;
  Vec3T<R> ui = xyz(vi), uj = xyz(vj);
  if constexpr (Law::needs_spin) {
    ui += cross(wi, arm * k.normal);
    uj += cross(wj, -arm_j * k.normal);
    k.relative_spin = wi - wj;
  }
  k.velocity = ui - uj;
  k.overlap_rate = dot(k.velocity, k.normal);
  k.reduced_mass = Real(1) / (vi.w + vj.w);
  if constexpr (Law::needs_effective_radius) k.effective_radius = xi.w * xj.w / (xi.w + xj.w);
  if constexpr (Law::needs_inertia) {
    const R inertia_i = sphere_inertia(xi.w, vi.w), inertia_j = sphere_inertia(xj.w, vj.w);
    k.reduced_inertia = inertia_i * inertia_j / (inertia_i + inertia_j);
    k.rolling_inertia = Real(1) / (Real(1) / inertia_about_contact(xi.w, vi.w) +
                                   Real(1) / inertia_about_contact(xj.w, vj.w));
  }
  if constexpr (Law::needs_contact_area)
    k.contact_radius_sq = sphere_contact_radius_sq(xi.w + xj.w - k.overlap, xi.w, xj.w);
}

/// Fills the fields of a wall contact that the law's flags ask for (wall: infinite mass
/// and radius; its surface moves with `wall_velocity` at the contact point).
template <class Law>
GPUDEM_HD void describe_wall(ContactSample<Law>& c, Real4 xi, Real4 vi, Vec3 wi,
                             Vec3 wall_velocity) {
  ContactPoint& k = c.point;
  Vec3 ui = xyz(vi) - wall_velocity;
  if constexpr (Law::needs_spin) {
    ui += cross(wi, c.arm * k.normal);
    k.relative_spin = wi;
  }
  k.velocity = ui;
  k.overlap_rate = dot(k.velocity, k.normal);
  k.reduced_mass = Real(1) / vi.w;
  if constexpr (Law::needs_effective_radius) k.effective_radius = xi.w;
  if constexpr (Law::needs_inertia) {
    k.reduced_inertia = sphere_inertia(xi.w, vi.w);
    k.rolling_inertia = inertia_about_contact(xi.w, vi.w);
  }
  if constexpr (Law::needs_contact_area)
    k.contact_radius_sq = wall_contact_radius_sq(xi.w, k.overlap);
}

/// How far past touch a contact of effective radius R* holds, given its stored history: the
/// cohesion's pull-off gap once the contact has formed, else 0 (contacts start at touch) [m].
template <class Law>
GPUDEM_HD Real holding_gap(const typename Law::Params& p, Real effective_radius,
                           const typename Law::State& state) {
  if constexpr (Law::Cohesion::history_size > 0) {
    if (Law::has_formed(state.value))
      return static_cast<Real>(
          Law::Cohesion::pull_off_gap(p, static_cast<typename Law::Scalar>(effective_radius)));
  }
  return 0;
}

/// True when every history value of `state` is zero (a contact that has none yet).
template <class State>
GPUDEM_HD bool is_blank(const State& state, int width) {
  for (int k = 0; k < width; ++k)
    if (state.value[k] != 0) return false;
  return true;
}

/// True when triangles s and t share a vertex.
GPUDEM_HD inline bool share_vertex(const TriangleIds& s, const TriangleIds& t) {
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      if (s.vertex[a] == t.vertex[b]) return true;
  return false;
}

/// History of the contact on list entry e: its own, or, when it has none yet, that of another
/// entry of the particle on a triangle sharing a vertex that is not in contact now — the
/// contact slid over from that triangle, and its spring goes with it.
template <class Law>
GPUDEM_HD typename Law::State mesh_contact_state(const ContactScene<Law>& s,
                                                 const MeshCandidateSpan& set, std::uint32_t begin,
                                                 std::uint32_t e) {
  typename Law::State state = s.mesh_history[e];
  if (!is_blank(state, Law::history_size)) return state;
  const TriangleIds& here = set.ids(e - begin);
  for (std::uint32_t k = 0; k < set.count; ++k) {
    if (set.is_contact(k) || is_blank(s.mesh_history[begin + k], Law::history_size)) continue;
    if (share_vertex(here, set.ids(k))) return s.mesh_history[begin + k];
  }
  return state;
}

/// The listed triangles of particle i (centre xi) within `reach` of its centre (its radius, or
/// more for a cohesion that holds contacts past touch), reduced to the contacts that count once
/// where triangles meet (select_mesh_contacts): fills the particle's candidates
/// (MeshView::candidates_of, one per list entry, contacts marked) and returns the number of
/// contacts. Each mesh meets the periodic image of i's centre nearest its image centre
/// (MeshView::image_for). The same for every law, so called, not inlined, by the device code
/// (GPUDEM_HD_CALLED).
GPUDEM_HD_CALLED inline int find_mesh_contacts(std::uint32_t i, Real4 xi, Real reach,
                                               const MeshView& m, const PeriodicBox& box) {
  const MeshCandidateSpan set = m.candidates_of(i);
  const std::uint32_t begin = m.offsets[i];
  for (std::uint32_t k = 0; k < set.count; ++k) {
    const std::uint32_t triangle = m.triangles[begin + k];
    const TriangleCorners t = m.corners[triangle];
    evaluate_mesh_candidate(set.items[k], m.image_for(box, xyz(xi), m.triangle_mesh[triangle]),
                            reach, m.vertices[t.v[0]], m.vertices[t.v[1]], m.vertices[t.v[2]],
                            m.ids[triangle]);
  }
  return select_mesh_contacts(set, reach);
}

/// How far past touch the mesh contacts of particle i (radius r, material mi) may hold: the
/// largest pull-off gap over the meshes when one of its list entries has formed, else 0 [m].
template <class Law>
GPUDEM_HD Real mesh_holding_gap(std::uint32_t i, Real radius, MaterialId mi,
                                const ContactScene<Law>& s) {
  Real gap = 0;
  if constexpr (Law::Cohesion::history_size > 0) {
    const MeshView& m = s.mesh;
    bool formed = false;
    for (std::uint32_t e = m.offsets[i]; e < m.offsets[i + 1]; ++e)
      formed = formed || Law::has_formed(s.mesh_history[e].value);
    if (!formed) return 0;
    for (std::uint32_t k = 0; k < m.mesh_count; ++k) {
      const Real g = static_cast<Real>(
          Law::Cohesion::pull_off_gap(s.pair_params[mi * s.material_count + m.material[k]],
                                      static_cast<typename Law::Scalar>(radius)));
      gap = g > gap ? g : gap;
    }
  }
  return gap;
}

/// The contact of particle i with the candidate on list entry e, its history not yet set.
template <class Law>
GPUDEM_HD ContactSample<Law> mesh_contact_sample(Real4 xi, Real4 vi, Vec3 wi, MaterialId mi,
                                                 const ContactScene<Law>& s,
                                                 const MeshContactCandidate& hit, std::uint32_t e) {
  const MeshView& m = s.mesh;
  const std::uint32_t mesh = m.triangle_mesh[hit.triangle];
  ContactSample<Law> c;
  c.point.normal = mesh_contact_normal(hit, m.image_for(s.box, xyz(xi), mesh));
  c.point.overlap = mesh_contact_overlap(hit, xi.w);
  c.arm = xi.w - Real(0.5) * c.point.overlap;
  describe_wall(c, xi, vi, wi, m.kinematics[mesh].at(hit.point));
  c.min_radius = xi.w;
  c.params = &s.pair_params[mi * s.material_count + m.material[mesh]];
  c.wall = -1;
  c.mesh = static_cast<std::int32_t>(mesh);
  c.slot = e;
  return c;
}

/// The mesh contacts of particle i (find_mesh_contacts) in list order, each visited with the
/// history of its list entry (mesh_contact_state); then the entries with no contact are
/// separated. A contact writes only its own entry and reads only its own or one not in contact,
/// so every history is read before it is written. With a cohesion that holds contacts past
/// touch, a particle with a formed mesh contact looks for contacts within its pull-off gap; one
/// found there that has not formed (nor carried over a formed history) is no contact.
template <class Law, class Visitor>
GPUDEM_HD void visit_mesh_contacts(std::uint32_t i, Real4 xi, Real4 vi, Vec3 wi, MaterialId mi,
                                   const ContactScene<Law>& s, Visitor& visit) {
  const MeshView& m = s.mesh;
  const Real gap = mesh_holding_gap(i, xi.w, mi, s);
  find_mesh_contacts(i, xi, xi.w + gap, m, s.box);
  const MeshCandidateSpan set = m.candidates_of(i);
  const std::uint32_t begin = m.offsets[i];
  for (std::uint32_t k = 0; k < set.count; ++k) {
    if (!set.is_contact(k)) continue;
    ContactSample<Law> c = mesh_contact_sample(xi, vi, wi, mi, s, set.items[k], begin + k);
    if constexpr (Law::history_size > 0) c.state = mesh_contact_state(s, set, begin, begin + k);
    if constexpr (Law::Cohesion::history_size > 0) {
      if (c.point.overlap <= -holding_gap<Law>(*c.params, xi.w, c.state)) {
        set.items[k].status = CandidateStatus::kInReach;
        continue;
      }
    }
    visit(c);
  }
  for (std::uint32_t k = 0; k < set.count; ++k)
    if (!set.is_contact(k)) visit.separated_from_mesh(begin + k);
}

/// The plane-wall contacts of particle i among the walls in its reach (WallReach.hpp), each wall
/// in order: positive overlap, or a formed contact within the cohesion's pull-off gap; the
/// others in reach are separated. The walls out of reach cannot touch it before the next list
/// build, and the build left their slots blank.
template <class Law, class Visitor>
GPUDEM_HD void visit_wall_contacts(std::uint32_t i, Real4 xi, Real4 vi, Vec3 wi, MaterialId mi,
                                   const ContactScene<Law>& s, Visitor& visit) {
  const WallReachBits reach{s.wall_count > 0 ? s.wall_reach[i] : 0u};
  if (reach.none()) return;
  for (std::uint32_t w = 0; w < s.wall_count; ++w) {
    if (!reach.holds(w)) continue;
    const PlaneWall& wall = s.walls[w];
    const Real overlap = wall_overlap(wall, xyz(xi), xi.w);
    const std::uint32_t slot = i * s.wall_count + w;
    Real gap = 0;
    if constexpr (Law::Cohesion::history_size > 0)
      if (overlap <= 0)
        gap = holding_gap<Law>(s.pair_params[mi * s.material_count + wall.material], xi.w,
                               s.wall_history[slot]);
    if (overlap <= -gap) {
      visit.separated_from_wall(slot);
      continue;
    }
    ContactSample<Law> c;
    c.point.normal = -wall.normal;
    c.point.overlap = overlap;
    c.arm = xi.w - Real(0.5) * overlap;
    describe_wall(c, xi, vi, wi, wall.velocity);
    c.min_radius = xi.w;
    c.params = &s.pair_params[mi * s.material_count + wall.material];
    c.wall = static_cast<std::int32_t>(w);
    c.slot = slot;
    if constexpr (Law::history_size > 0) c.state = s.wall_history[slot];
    visit(c);
  }
}

/// Particle i as a contact sweep reads it.
struct SweptParticle {
  Real4 x;  ///< position and radius
  Real4 v;  ///< velocity and inverse mass
  Vec3 w;   ///< spin (zero for a law without spin)
  MaterialId material;
};

template <class Law, class P>
GPUDEM_HD SweptParticle swept_particle(std::uint32_t i, const ParticleView<P>& p) {
  SweptParticle q{p.position(i), p.velocity(i), Vec3{}, p.material[i]};
  if constexpr (Law::needs_spin) q.w = p.spin(i);
  return q;
}

/// Particle i's partner on one list entry as a contact sweep first sees it.
struct PairEntry {
  std::uint32_t j;  ///< the partner
  bool touching;    ///< whether the pair is a contact now
  Real4 xj;         ///< the partner's centre and radius (when not bonded)
  Vec3 d;           ///< x_j − x_i, nearest image
  Real dist2;       ///< |d|²
};

/// Whether particle i (`me`) and its partner j on list entry k touch: positive overlap, or, for a
/// cohesion that holds contacts past touch (JKR), a formed contact within its pull-off gap; a
/// bonded pair never does.
template <class Law, class P>
GPUDEM_HD PairEntry pair_entry(const SweptParticle& me, std::uint32_t k, std::uint32_t j,
                               const ParticleView<P>& p, const ContactScene<Law>& s) {
  PairEntry e{j, false, {}, {}, 0};
  if (s.bonded(k)) return e;
  const Real4 xi = me.x;
  e.xj = p.position(e.j);
  e.d = s.box.minimum_image(xyz(e.xj) - xyz(xi));
  e.dist2 = norm2(e.d);
  const Real reach = xi.w + e.xj.w;
  Real limit = reach;
  if constexpr (Law::Cohesion::history_size > 0)
    if (e.dist2 >= reach * reach)
      limit += holding_gap<Law>(s.pair_params[me.material * s.material_count + p.material[e.j]],
                                xi.w * e.xj.w / reach, s.pair_history[k]);
  e.touching = !(e.dist2 >= limit * limit || e.dist2 == 0);  // NaN: touching, so it spreads
  return e;
}

/// Calls visit(sample) when particle i (`me`) and its partner j on list entry k touch
/// (pair_entry), and visit.separated(k) otherwise.
template <class Law, class P, class Visitor>
GPUDEM_HD void visit_pair_entry(const SweptParticle& me, std::uint32_t k, std::uint32_t j,
                                const ParticleView<P>& p, const ContactScene<Law>& s,
                                Visitor& visit) {
  const PairEntry e = pair_entry(me, k, j, p, s);
  if (!e.touching) {
    visit.separated(k);
    return;
  }
  ContactSample<Law> c;
  Vec3 wj{};
  if constexpr (Law::needs_spin) wj = p.spin(e.j);
  describe_pair<Law>(c.point, c.arm, e.d, e.dist2, me.x, me.v, me.w, e.xj, p.velocity(e.j), wj);
  c.min_radius = me.x.w < e.xj.w ? me.x.w : e.xj.w;
  c.params = &s.pair_params[me.material * s.material_count + p.material[e.j]];
  c.wall = -1;
  c.slot = k;
  if constexpr (Law::history_size > 0) c.state = s.pair_history[k];
  visit(c);
}

/// The plane-wall and mesh contacts of particle i (after its pairs).
template <class Law, class Visitor>
GPUDEM_HD void visit_body_contacts(std::uint32_t i, const SweptParticle& me,
                                   const ContactScene<Law>& s, Visitor& visit) {
  visit_wall_contacts(i, me.x, me.v, me.w, me.material, s, visit);
  if (s.mesh.mesh_count > 0) visit_mesh_contacts(i, me.x, me.v, me.w, me.material, s, visit);
}

/// Calls visit(sample) for each contact of particle i: its list entries in order
/// (visit_pair_entry), then plane walls and meshes.
template <class Law, class P, class Visitor>
GPUDEM_HD void for_each_contact(std::uint32_t i, const ParticleView<P>& p,
                                const ContactScene<Law>& s, Visitor& visit) {
  const SweptParticle me = swept_particle<Law>(i, p);
  for (std::uint32_t k = s.neighbor_offsets[i]; k < s.neighbor_offsets[i + 1]; ++k)
    visit_pair_entry(me, k, s.neighbor_index[k], p, s, visit);
  visit_body_contacts(i, me, s, visit);
}

}  // namespace gpudem
