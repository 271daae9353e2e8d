#include "engine/MeshStartOverlap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/InputError.hpp"
#include "engine/TriangleContact.hpp"

namespace gpudem {
namespace {

struct Box {
  Vec3 lo, hi;
  bool meets(const Box& o) const {
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z &&
           o.lo.z <= hi.z;
  }
};

Box box_of(std::initializer_list<Vec3> points) {
  Box b{*points.begin(), *points.begin()};
  for (const Vec3& p : points)
    for (int k = 0; k < 3; ++k) {
      axis(b.lo, k) = std::min(axis(b.lo, k), axis(p, k));
      axis(b.hi, k) = std::max(axis(b.hi, k), axis(p, k));
    }
  return b;
}

Box sphere_box(const Real4& p) {
  const Vec3 r{p.w, p.w, p.w};
  return {xyz(p) - r, xyz(p) + r};
}

/// x with three significant digits.
std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

/// The overlaps of all ranks, from each rank's: counts summed, the deepest (by ratio) kept
/// with its place. Collective.
MeshStartOverlap over_ranks(const MeshStartOverlap& mine, const RankGroup& ranks) {
  MeshStartOverlap all = mine;
  all.particles = ranks.sum(mine.particles);
  all.deepest_ratio = ranks.max(mine.deepest_ratio);
  if (all.particles == 0) return all;
  const int holder =
      ranks.first_rank_with(mine.particles > 0 && mine.deepest_ratio == all.deepest_ratio);
  all.deepest = ranks.broadcast_value(mine.deepest, holder);
  all.deepest_at = ranks.broadcast_value(mine.deepest_at, holder);
  return all;
}

std::string describe(const std::string& mesh, const MeshStartOverlap& o) {
  return "mesh '" + mesh + "' overlaps " + std::to_string(o.particles) +
         " particle(s) at t = 0, the deepest by " + number(o.deepest) + " m (" +
         number(100 * o.deepest_ratio) + " % of its radius) at (" + number(o.deepest_at.x) + ", " +
         number(o.deepest_at.y) + ", " + number(o.deepest_at.z) + ") m";
}

}  // namespace

MeshStartOverlap mesh_start_overlap(const TriangleMesh& mesh, const ParticleStore& particles) {
  MeshStartOverlap out;
  if (mesh.vertices.empty()) return out;
  std::vector<Box> triangle_box;
  triangle_box.reserve(mesh.triangles.size());
  Box whole{mesh.vertices.front(), mesh.vertices.front()};
  for (const auto& t : mesh.triangles) {
    triangle_box.push_back(box_of({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]}));
    whole = box_of({whole.lo, whole.hi, triangle_box.back().lo, triangle_box.back().hi});
  }
  for (const Real4& p : particles.position_radius) {
    const Box reach = sphere_box(p);
    if (!reach.meets(whole)) continue;
    double nearest2 = HUGE_VAL;
    for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
      if (!reach.meets(triangle_box[k])) continue;
      const auto& t = mesh.triangles[k];
      const TriangleFeature f = closest_triangle_feature(xyz(p), mesh.vertices[t[0]],
                                                         mesh.vertices[t[1]], mesh.vertices[t[2]]);
      nearest2 = std::min(nearest2, norm2(f.point - xyz(p)));
    }
    const double overlap = p.w - std::sqrt(nearest2);
    if (!(overlap > 0)) continue;
    ++out.particles;
    if (overlap / p.w > out.deepest_ratio) {
      out.deepest_ratio = overlap / p.w;
      out.deepest = overlap;
      out.deepest_at = xyz(p);
    }
  }
  return out;
}

std::vector<std::string> check_mesh_start_overlaps(const Scene& scene,
                                                   const std::vector<MeshWallSetup>& meshes,
                                                   const ParticleStore& share,
                                                   const RankGroup& ranks) {
  std::vector<std::string> warnings;
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const MeshSettings& settings = scene.meshes[i];
    const MeshStartOverlap o = over_ranks(mesh_start_overlap(meshes[i].mesh, share), ranks);
    if (o.particles == 0) continue;
    if (o.deepest_ratio > kLargestStartOverlap)
      throw InputError(scene.file, settings.offset_line, "mesh[" + std::to_string(i) + "].offset",
                       describe(settings.name, o) + ", more than " +
                           number(100 * kLargestStartOverlap) +
                           " % of a radius: place it clear of the particles (its offset, "
                           "rotation and scale) and let its motion bring it in");
    warnings.push_back(describe(settings.name, o) + " (resting contacts)");
  }
  return warnings;
}

}  // namespace gpudem
