#include "core/ImplementLoads.hpp"

#include "core/Rotation.hpp"

namespace gpudem {

namespace {

void append_frame(const FrameLoads& f, std::vector<double>& row) {
  row.insert(row.end(), {f.draft, f.vertical, f.lateral, f.moment_forward, f.moment_lateral,
                         f.moment_vertical});
}

}  // namespace

FrameLoads frame_loads(Vec3 force, Vec3 torque, const Rotation& turned, Vec3 forward, Vec3 up) {
  const Vec3 f = turned.apply(forward), u = turned.apply(up), l = cross(u, f);
  return {-dot(force, f), dot(force, u),  dot(force, l),
          dot(torque, f), dot(torque, l), dot(torque, u)};
}

ImplementLoads::ImplementLoads(const Scene& scene) {
  for (const ImplementSettings& im : scene.implements)
    implements_.push_back({&im, PrescribedMotion(im.reference, im.keyframes)});
}

std::vector<double> ImplementLoads::row(double t, const std::vector<Vec3>& mesh_force,
                                        const std::vector<Vec3>& mesh_torque) const {
  std::vector<double> row;
  for (const Implement& im : implements_) {
    const ImplementSettings& s = *im.settings;
    const Rotation turned = rotation_by_vector(im.motion.rotation_vector(0, t));
    Vec3 force{}, torque{};
    for (std::size_t m : s.meshes) {
      force += mesh_force[m];
      torque += mesh_torque[m];
    }
    row.insert(row.end(), {force.x, force.y, force.z, torque.x, torque.y, torque.z});
    append_frame(frame_loads(force, torque, turned, s.forward, s.up), row);
    for (std::size_t m : s.meshes)
      append_frame(frame_loads(mesh_force[m], mesh_torque[m], turned, s.forward, s.up), row);
  }
  return row;
}

}  // namespace gpudem
