#pragma once
/// The triangle-mesh walls (tools) of a step engine in one memory space: vertices moved
/// rigidly by their prescribed motion every step, the per-particle triangle candidate lists
/// rebuilt with the neighbour list, and the contact history of each (particle, listed
/// triangle) entry, carried over a rebuild (and a migration to another rank) by (particle,
/// triangle index). Every rank holds every vertex (a rigid tool moves through all blocks; its
/// vertices cost 72 bytes each), but bins only the triangles that meet its region. In a box
/// with periodic axes each mesh meets the periodic image of a particle nearest the mesh's image
/// centre: the centre of its bounding box at t = 0, moved rigidly with the mesh. Include the
/// backend's ParallelFor header first.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/Rotation.hpp"
#include "engine/ArrayKernels.hpp"
#include "engine/CsrRows.hpp"
#include "engine/DeviceArray.hpp"
#include "engine/MeshCandidateList.hpp"
#include "engine/MeshWallSetup.hpp"

namespace gpudem {

/// Rigid motion of one mesh at the current time, for the velocity of its surface.
struct MeshKinematics {
  Vec3 velocity;          ///< of the centre [m/s]
  Vec3 angular_velocity;  ///< [rad/s]
  Vec3 centre;            ///< [m]
  /// Velocity of the mesh point x: v + ω × (x − c) [m/s].
  GPUDEM_HD Vec3 at(Vec3 x) const { return velocity + cross(angular_velocity, x - centre); }
};

/// What the contact sweep reads about the meshes (pointers into one memory space).
struct MeshView {
  std::uint32_t mesh_count = 0;
  const Vec3* vertices = nullptr;
  const TriangleCorners* corners = nullptr;
  const TriangleIds* ids = nullptr;  ///< vertex and edge ids unique over all meshes
  const std::uint32_t* triangle_mesh = nullptr;
  const MaterialId* material = nullptr;        ///< per mesh
  const MeshKinematics* kinematics = nullptr;  ///< per mesh
  const std::uint32_t* offsets = nullptr;      ///< per-particle candidate lists (CSR)
  const std::uint32_t* triangles = nullptr;
  const Vec3* image_centre = nullptr;  ///< per mesh [m]
  /// Per candidate-list entry: the closest point of its triangle at the last contact sweep, the
  /// working memory of find_mesh_contacts (written by the sweep of the entry's particle only).
  MeshContactCandidate* candidates = nullptr;

  /// The candidates of particle i, one per listed triangle.
  GPUDEM_HD MeshCandidateSpan candidates_of(std::uint32_t i) const {
    return {candidates + offsets[i], offsets[i + 1] - offsets[i], ids};
  }

  /// The periodic image of the particle centre x that mesh `mesh` meets: the one nearest the
  /// mesh's image centre (x itself without periodic axes).
  GPUDEM_HD Vec3 image_for(const PeriodicBox& box, Vec3 x, std::uint32_t mesh) const {
    return box.image_near(x, image_centre[mesh]);
  }
};

namespace mesh_wall_kernels {

/// x = R (x₀ − c₀) + c for the vertices [first, first + count) of one mesh.
struct PlaceVertices {
  const Vec3* initial;
  Vec3* current;
  std::size_t first;
  Rotation rotation;
  Vec3 initial_centre;
  Vec3 centre;
  GPUDEM_HD void operator()(std::size_t k) const {
    current[first + k] = rotation.apply(initial[first + k] - initial_centre) + centre;
  }
};

/// |x − x_at_build|² of vertex k.
struct VertexDisplacement {
  const Vec3* current;
  const Vec3* at_build;
  GPUDEM_HD Real operator()(std::size_t k) const { return norm2(current[k] - at_build[k]); }
};

/// History of particle k's new list entries (`width` values each) from its old entries with the
/// same triangle.
template <class S>
struct RemapEntries {
  const std::uint32_t* offsets;
  const std::uint32_t* triangles;
  const std::uint32_t* previous_index;
  const std::uint32_t* previous_offsets;
  const std::uint32_t* previous_triangles;
  const S* previous_history;
  S* history;
  std::uint32_t width;
  GPUDEM_HD void operator()(std::size_t k) const {
    const std::uint32_t old = previous_index[k];
    for (std::uint32_t e = offsets[k]; e < offsets[k + 1]; ++e) {
      S* record = history + std::size_t(e) * width;
      for (std::uint32_t v = 0; v < width; ++v) record[v] = S{};
      for (std::uint32_t f = previous_offsets[old]; f < previous_offsets[old + 1]; ++f)
        if (previous_triangles[f] == triangles[e]) {
          for (std::uint32_t v = 0; v < width; ++v)
            record[v] = previous_history[std::size_t(f) * width + v];
          break;
        }
    }
  }
};

}  // namespace mesh_wall_kernels

/// Each candidate-list entry keeps `history_width` values of scalar S (the contact law's
/// history; none when 0).
template <class Space, class S>
class MeshWalls {
 public:
  MeshWalls() = default;
  MeshWalls(const std::vector<MeshWallSetup>& meshes, const PeriodicBox& box,
            std::uint32_t history_width)
      : setups_(meshes), box_(box), history_width_(history_width) {
    kept_.value_width = history_width;
    std::vector<Vec3> vertices;
    std::vector<TriangleCorners> corners;
    std::vector<TriangleIds> ids;
    std::vector<std::uint32_t> triangle_mesh;
    std::vector<MaterialId> material;
    std::uint32_t edge_base = 0;
    for (std::uint32_t m = 0; m < meshes.size(); ++m) {
      const TriangleMesh& mesh = meshes[m].mesh;
      const auto vertex_base = static_cast<std::uint32_t>(vertices.size());
      first_vertex_.push_back(vertices.size());
      vertices.insert(vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
      for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        TriangleIds id;
        id.triangle = static_cast<std::uint32_t>(ids.size());
        for (int k = 0; k < 3; ++k) {
          id.vertex[k] = vertex_base + mesh.triangles[t][k];
          id.edge[k] = edge_base + mesh.triangle_edges[t][k];
        }
        corners.push_back({{id.vertex[0], id.vertex[1], id.vertex[2]}});
        ids.push_back(id);
        triangle_mesh.push_back(m);
      }
      edge_base += static_cast<std::uint32_t>(mesh.edges.size());
      material.push_back(meshes[m].material);
      initial_image_centre_.push_back(bounding_box_centre(mesh.vertices));
    }
    first_vertex_.push_back(vertices.size());
    initial_.upload(vertices);
    vertices_.upload(vertices);
    at_build_.upload(vertices);
    corners_.upload(corners);
    ids_.upload(ids);
    triangle_mesh_.upload(triangle_mesh);
    material_.upload(material);
    set_time(0);
  }

  std::uint32_t count() const { return static_cast<std::uint32_t>(setups_.size()); }
  bool empty() const { return setups_.empty(); }

  /// Moves every mesh to its pose at time t (from its initial pose, so no error accumulates)
  /// and records its surface velocity and its image centre at t: b(t) = R(t)(b₀ − c₀) + c(t),
  /// b₀ the initial one, R(t) the rotation by ∫₀ᵗ ω, c the rotation centre. Where no mesh has
  /// a prescribed motion, the first call's poses hold for every t and later calls do nothing.
  void set_time(double t) {
    if (poses_fixed_) return;
    std::vector<MeshKinematics> kinematics;
    std::vector<Vec3> image_centre = initial_image_centre_;
    for (std::uint32_t m = 0; m < count(); ++m) {
      const PrescribedMotion& motion = setups_[m].motion;
      const Vec3 centre = motion.centre(t);
      kinematics.push_back({motion.velocity(t), motion.angular_velocity(t), centre});
      if (motion.stands_still()) continue;  // its vertices keep their initial positions
      const Rotation rotation = rotation_by_vector(motion.rotation_vector(0, t));
      image_centre[m] = rotation.apply(image_centre[m] - motion.centre(0)) + centre;
      const std::size_t n = first_vertex_[m + 1] - first_vertex_[m];
      parallel_for(
          Space{}, n,
          mesh_wall_kernels::PlaceVertices{initial_.data(), vertices_.data(), first_vertex_[m],
                                           rotation, motion.centre(0), centre});
    }
    kinematics_.upload(kinematics);
    image_centre_.upload(image_centre);
    poses_fixed_ = std::all_of(setups_.begin(), setups_.end(), [](const MeshWallSetup& mesh) {
      return mesh.motion.stands_still();
    });
  }

  /// True once some vertex has moved more than skin/2 since the last build.
  bool moved_beyond(Real half_skin) const {
    if (empty() || poses_fixed_) return false;
    const Real moved2 =
        reduce_max(Space{}, vertices_.size(), Real(0),
                   mesh_wall_kernels::VertexDisplacement{vertices_.data(), at_build_.data()});
    return moved2 > half_skin * half_skin;
  }

  /// Keeps the current lists' history as rows keyed by triangle index, for the next rebuild
  /// (call before the particles are reordered or migrated; their rows follow previous_index).
  void keep_rows() {
    if (history_width_ > 0) {
      if (empty()) return;
      copy_values(candidates_.offsets(), candidates_.size() + 1, kept_.offsets);
      copy_values(candidates_.triangles(), candidates_.pairs(), kept_.keys);
      kept_.values.swap(history_);
    }
  }

  /// The kept rows: those of the owned particles at keep time (each read through its
  /// previous_index), then those of particles that arrived from other ranks, appended.
  CsrRows<Space, std::uint32_t, S>& kept_rows() { return kept_; }
  const CsrRows<Space, std::uint32_t, S>& kept_rows() const { return kept_; }

  /// New candidate lists for the n particles (in their new order, all inside `region` on
  /// this rank), with the history carried over from the kept rows: previous_index[k] is
  /// particle k's row there (`had_lists` false: no rows kept, history starts at zero).
  /// `max_radius` is the largest radius on all ranks.
  template <class P>
  void rebuild(const Vec4T<P>* position_radius, std::size_t n, Real max_radius, Real skin,
               const BinRegion& region, const std::uint32_t* previous_index, bool had_lists) {
    if (empty()) return;
    const MeshImages images{box_, count(), triangle_mesh_.data(), image_centre_.data()};
    candidates_.build(vertices_.data(), vertices_.size(), corners_.data(), ids_.size(), region,
                      images, position_radius, n, max_radius, skin);
    parallel_for(Space{}, vertices_.size(), CopyArray<Vec3>{vertices_.data(), at_build_.data()});
    sweep_candidates_.resize(candidates_.pairs());
    if (history_width_ > 0) {
      DeviceArray<S, Space> fresh(candidates_.pairs() * history_width_);
      if (had_lists) {
        parallel_for(Space{}, n,
                     mesh_wall_kernels::RemapEntries<S>{
                         candidates_.offsets(), candidates_.triangles(), previous_index,
                         kept_.offsets.data(), kept_.keys.data(), kept_.values.data(), fresh.data(),
                         history_width_});
      } else {
        parallel_for(Space{}, fresh.size(), Fill<S>{fresh.data(), S{}});
      }
      history_.swap(fresh);
    }
  }

  /// Host copy of the candidate lists' CSR offsets over the owned particles (none without
  /// meshes).
  std::vector<std::uint32_t> entry_offsets() const {
    return download_values<Space>(candidates_.offsets(), empty() ? 0 : candidates_.size() + 1);
  }

  /// Host copy of the history of each candidate-list entry (history_width values each).
  std::vector<S> entry_history() const {
    std::vector<S> history;
    history_.download(history);
    return history;
  }

  /// Replaces the history of the candidate-list entries (history_width values each).
  void set_history(const std::vector<S>& history) { history_.upload(history); }

  /// Triangles in all meshes.
  std::uint32_t triangle_count() const { return static_cast<std::uint32_t>(ids_.size()); }

  /// Host copy of mesh m's vertices at the current pose, numbered as in its setup.
  std::vector<Vec3> current_vertices(std::uint32_t m) const {
    return download_values<Space>(vertices_.data() + first_vertex_[m],
                                  first_vertex_[m + 1] - first_vertex_[m]);
  }
  /// Mesh m's triangles as set up (vertex ids of mesh m); the triangles of all meshes, in
  /// this order mesh by mesh, are the global triangle indices of the candidate lists.
  const std::vector<std::array<std::uint32_t, 3>>& setup_triangles(std::uint32_t m) const {
    return setups_[m].mesh.triangles;
  }
  /// Host copy of the global triangle index of each candidate-list entry.
  std::vector<std::uint32_t> entry_triangles() const {
    return download_values<Space>(candidates_.triangles(), empty() ? 0 : candidates_.pairs());
  }

  MeshView view() const {
    if (empty()) return MeshView{};
    return MeshView{count(),
                    vertices_.data(),
                    corners_.data(),
                    ids_.data(),
                    triangle_mesh_.data(),
                    material_.data(),
                    kinematics_.data(),
                    candidates_.offsets(),
                    candidates_.triangles(),
                    image_centre_.data(),
                    sweep_candidates_.data()};
  }
  S* history() { return history_.data(); }
  /// History values of all candidate-list entries.
  std::size_t history_values() const { return history_.size(); }
  const S* history() const { return history_.data(); }
  std::size_t memory_bytes() const {
    return initial_.bytes() + vertices_.bytes() + at_build_.bytes() + corners_.bytes() +
           ids_.bytes() + triangle_mesh_.bytes() + history_.bytes() + candidates_.memory_bytes() +
           sweep_candidates_.bytes() + kept_.bytes();
  }

 private:
  /// Centre of the bounding box of the points [m].
  static Vec3 bounding_box_centre(const std::vector<Vec3>& points) {
    if (points.empty()) return Vec3{};
    Vec3 lo = points.front(), hi = points.front();
    for (const Vec3& p : points)
      for (int k = 0; k < 3; ++k) {
        axis(lo, k) = std::min(axis(lo, k), axis(p, k));
        axis(hi, k) = std::max(axis(hi, k), axis(p, k));
      }
    return Real(0.5) * (lo + hi);
  }

  std::vector<MeshWallSetup> setups_;
  std::vector<std::size_t> first_vertex_;  ///< mesh m's vertices: [first[m], first[m + 1])
  PeriodicBox box_;
  std::vector<Vec3> initial_image_centre_;  ///< b₀ of each mesh [m]
  bool poses_fixed_ = false;                ///< no mesh moves, and set_time has placed them once
  DeviceArray<Vec3, Space> initial_;
  DeviceArray<Vec3, Space> vertices_;
  DeviceArray<Vec3, Space> at_build_;
  DeviceArray<TriangleCorners, Space> corners_;
  DeviceArray<TriangleIds, Space> ids_;
  DeviceArray<std::uint32_t, Space> triangle_mesh_;
  DeviceArray<MaterialId, Space> material_;
  DeviceArray<MeshKinematics, Space> kinematics_;
  DeviceArray<Vec3, Space> image_centre_;  ///< per mesh, at the time of set_time [m]
  MeshCandidateList<Space> candidates_;
  std::uint32_t history_width_ = 0;  ///< history values per candidate-list entry
  DeviceArray<S, Space> history_;    ///< per candidate-list entry
  /// Per candidate-list entry, the contact sweep's working memory (MeshView::candidates): not
  /// state, so a const view may hand it out for writing.
  mutable DeviceArray<MeshContactCandidate, Space> sweep_candidates_;
  // The rows kept for the next rebuild: per particle, (triangle, history) entries.
  CsrRows<Space, std::uint32_t, S> kept_;
};

}  // namespace gpudem
