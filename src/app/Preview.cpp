#include "app/Preview.hpp"

#include <fstream>
#include <string>
#include <vector>

#include "comm/Hdf5Io.hpp"
#include "comm/OutputDirectory.hpp"
#include "comm/XdmfDocument.hpp"
#include "core/PreviewImage.hpp"

namespace gpudem {

namespace {

constexpr int kPathSamples = 101;

/// Everything the preview shows but the particles, worked out alike on every rank.
PreviewContent scene_geometry(const Scene& scene, const EngineSetup& setup) {
  PreviewContent c;
  c.domain_lo = scene.domain.min;
  c.domain_hi = scene.domain.max;
  for (const WallSettings& w : scene.walls)
    c.walls.push_back(wall_in_box(w.point, w.normal, c.domain_lo, c.domain_hi));
  const double end = scene.simulation.end_time;
  for (const MeshWallSetup& m : setup.meshes) {
    c.mesh_start.push_back({m.mesh.vertices, m.mesh.triangles});
    c.mesh_end.push_back({vertices_at(m.mesh.vertices, m.motion, end), m.mesh.triangles});
    c.paths.push_back(m.motion.stands_still() ? std::vector<Vec3>{}
                                              : centre_path(m.motion, end, kPathSamples));
  }
  return c;
}

/// Rows written by rank 0 alone (the others take part with none).
Slice root_rows(const MpiContext& mpi, std::size_t n) { return Slice{0, mpi.is_root() ? n : 0, n}; }

void write_surface(const ParallelFile& file, const MpiContext& mpi, const std::string& group,
                   const PreviewSurface& s) {
  const std::string vertices = group + "/vertices", triangles = group + "/triangles";
  file.write_dataset(
      {vertices.c_str(), s.vertices.data(), native_type<Real>(), H5T_IEEE_F64LE, 3, 3, 0},
      root_rows(mpi, s.vertices.size()));
  file.write_dataset(
      {triangles.c_str(), s.triangles.data(), H5T_NATIVE_UINT32, H5T_STD_U32LE, 3, 3, 0},
      root_rows(mpi, s.triangles.size()));
}

void write_particles(const ParallelFile& file, const MpiContext& mpi, const ParticleStore& p) {
  const Slice slice = global_slice(mpi.comm(), p.size());
  std::vector<std::uint64_t> rows(p.size());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = slice.offset + i;
  const hid_t real = native_type<Real>();
  file.write_dataset(
      {"particles/position", p.position_radius.data(), real, H5T_IEEE_F64LE, 3, 4, 0}, slice);
  file.write_dataset({"particles/radius", p.position_radius.data(), real, H5T_IEEE_F64LE, 1, 4, 3},
                     slice);
  file.write_dataset({"particles/material", p.material.data(), native_type<MaterialId>(),
                      stored_type<MaterialId>(), 1, 1, 0},
                     slice);
  file.write_dataset(
      {"particles/connectivity", rows.data(), H5T_NATIVE_UINT64, H5T_STD_U64LE, 1, 1, 0}, slice);
}

void write_h5(const std::string& path, const Scene& scene, const PreviewContent& c,
              const ParticleStore& share, const MpiContext& mpi) {
  const H5Calls h5("preview", path);
  ParallelFile file(mpi.comm(), h5, path);
  write_particles(file, mpi, share);
  for (std::size_t m = 0; m < c.mesh_start.size(); ++m) {
    write_surface(file, mpi, "mesh/" + scene.meshes[m].name, c.mesh_start[m]);
    write_surface(file, mpi, "mesh_end/" + scene.meshes[m].name, c.mesh_end[m]);
    if (c.paths[m].empty()) continue;  // a mesh that stands still
    const std::string path_name = "path/" + scene.meshes[m].name;
    file.write_dataset(
        {path_name.c_str(), c.paths[m].data(), native_type<Real>(), H5T_IEEE_F64LE, 3, 3, 0},
        root_rows(mpi, c.paths[m].size()));
  }
  for (std::size_t w = 0; w < c.walls.size(); ++w)
    write_surface(file, mpi, "wall/" + scene.walls[w].name, c.walls[w]);
  file.close();
}

std::string surface_grid(const std::string& name, const std::string& group,
                         const PreviewSurface& s) {
  using namespace xdmf_detail;
  return "      <Grid Name=\"" + escape(name) + "\" GridType=\"Uniform\">\n" +
         "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"" +
         std::to_string(s.triangles.size()) + "\">\n          " +
         hdf_item("preview.h5", group + "/triangles", "UInt", 4, s.triangles.size(), 3) +
         "\n        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n          " +
         hdf_item("preview.h5", group + "/vertices", "Float", 8, s.vertices.size(), 3) +
         "\n        </Geometry>\n      </Grid>\n";
}

std::string particle_grid(std::uint64_t count) {
  using namespace xdmf_detail;
  return "      <Grid Name=\"particles\" GridType=\"Uniform\">\n"
         "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" +
         std::to_string(count) + "\" NodesPerElement=\"1\">\n          " +
         hdf_item("preview.h5", "particles/connectivity", "UInt", 8, count, 1) +
         "\n        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n          " +
         hdf_item("preview.h5", "particles/position", "Float", 8, count, 3) +
         "\n        </Geometry>\n" +
         attribute_element("radius", "Scalar", "Node",
                           hdf_item("preview.h5", "particles/radius", "Float", 8, count, 1)) +
         attribute_element("material", "Scalar", "Node",
                           hdf_item("preview.h5", "particles/material", "UInt", 4, count, 1)) +
         "      </Grid>\n";
}

/// A Polyline of the path's points in order, its connectivity given inline.
std::string path_grid(const std::string& name, const std::vector<Vec3>& path) {
  using namespace xdmf_detail;
  std::string order;
  for (std::size_t k = 0; k < path.size(); ++k) order += (k ? " " : "") + std::to_string(k);
  return "      <Grid Name=\"" + escape(name) + "_path\" GridType=\"Uniform\">\n" +
         "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"1\" NodesPerElement=\"" +
         std::to_string(path.size()) +
         "\">\n          <DataItem Format=\"XML\" NumberType=\"UInt\" Dimensions=\"1 " +
         std::to_string(path.size()) + "\">" + order +
         "</DataItem>\n        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n          " +
         hdf_item("preview.h5", "path/" + name, "Float", 8, path.size(), 3) +
         "\n        </Geometry>\n      </Grid>\n";
}

void write_xmf(const std::string& path, const Scene& scene, const PreviewContent& c,
               std::uint64_t particle_count) {
  std::string grids = particle_grid(particle_count);
  for (std::size_t m = 0; m < c.mesh_start.size(); ++m) {
    const std::string& name = scene.meshes[m].name;
    grids += surface_grid(name, "mesh/" + name, c.mesh_start[m]);
    grids += surface_grid(name + "_end", "mesh_end/" + name, c.mesh_end[m]);
    if (!c.paths[m].empty()) grids += path_grid(name, c.paths[m]);
  }
  for (std::size_t w = 0; w < c.walls.size(); ++w)
    if (!c.walls[w].triangles.empty())
      grids += surface_grid(scene.walls[w].name, "wall/" + scene.walls[w].name, c.walls[w]);
  std::ofstream(path) << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n"
                         "    <Grid Name=\"preview\" GridType=\"Collection\" "
                         "CollectionType=\"Spatial\">\n"
                      << grids << "    </Grid>\n  </Domain>\n</Xdmf>\n";
}

/// Every k-th particle of each rank, k chosen so that at most kPreviewImageParticles are
/// drawn, gathered into `c` on every rank. Collective.
void gather_image_particles(const ParticleStore& share, std::uint64_t total, const MpiContext& mpi,
                            PreviewContent& c) {
  const std::uint64_t stride = (total + kPreviewImageParticles - 1) / kPreviewImageParticles;
  std::vector<Real4> mine;
  std::vector<MaterialId> material;
  for (std::size_t i = 0; i<share.size(); i += stride> 0 ? stride : 1) {
    mine.push_back(share.position_radius[i]);
    material.push_back(share.material[i]);
  }
  for (const Real4& p : mpi.group().gather(mine)) {
    c.centres.push_back(xyz(p));
    c.radius.push_back(p.w);
  }
  for (MaterialId m : mpi.group().gather(material)) c.material.push_back(m);
}

}  // namespace

void write_preview(const Scene& scene, const EngineSetup& setup, const ParticleStore& share,
                   const MpiContext& mpi) {
  const std::string dir = scene.output.dir;
  prepare_output_directory(dir);
  PreviewContent content = scene_geometry(scene, setup);
  const std::uint64_t total = mpi.group().sum<std::uint64_t>(share.size());
  write_h5(dir + "/preview.h5", scene, content, share, mpi);
  gather_image_particles(share, total, mpi, content);
  if (!mpi.is_root()) return;
  write_xmf(dir + "/preview.xmf", scene, content, total);
  const std::vector<std::uint8_t> png = render_preview(content).png();
  std::ofstream(dir + "/preview.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
}

}  // namespace gpudem
