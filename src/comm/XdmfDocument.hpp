#pragma once
/// XDMF 3 description of snapshots: one temporal collection holding, per snapshot, a
/// Polyvertex grid whose heavy data are the datasets SnapshotWriter puts at the root of that
/// snapshot's HDF5 file, and for each mesh wall a collection of Triangle grids read from group
/// `/mesh/<name>/` of the same files. Files are named relative to the .xmf, so an output folder
/// can be moved as a whole. Keys are the ones both ParaView readers accept (Xdmf3 and the
/// legacy Xdmf2).
#include <cstdint>
#include <string>
#include <vector>

#include "core/ExactDecimal.hpp"
#include "core/OutputNames.hpp"

namespace gpudem {

/// What a snapshot file holds beside dataset "position", and in what precision.
struct SnapshotLayout {
  bool rank_field = false;                    ///< dataset "rank": the MPI rank owning each particle
  std::uint32_t fields = kAllSnapshotFields;  ///< the datasets of kSnapshotFields it holds
  bool single_precision = false;  ///< real-valued particle datasets in float32, not float64
};

/// One snapshot as the XDMF document lists it.
struct XdmfSnapshot {
  std::string h5_file;           ///< HDF5 file name relative to the .xmf
  double time = 0;               ///< simulated time [s]
  std::uint64_t count = 0;       ///< number of particles (all ranks)
  SnapshotLayout layout;         ///< what the file holds
  std::uint64_t bond_count = 0;  ///< bonds in its group `/bonds/` (snapshots with bonds)
};

/// A mesh wall as its XDMF document lists it; its counts do not change during a run.
struct XdmfMesh {
  std::string name;                  ///< the mesh's name: group `/mesh/<name>/`, `<name>.xmf`
  std::uint64_t vertex_count = 0;    ///< rows of dataset `vertices`
  std::uint64_t triangle_count = 0;  ///< rows of datasets `triangles`, `force`, `pressure`
};

/// A per-particle dataset shown as an XDMF attribute.
struct XdmfField {
  const char* name;            ///< dataset name at the file root, also the attribute name
  const char* attribute_type;  ///< "Scalar" or "Vector"
  const char* number_type;     ///< "Float" or "UInt"
  int precision;               ///< bytes per value of a UInt field (Float: real_precision)
  int components;              ///< values per particle
};

/// The particle attributes a snapshot may hold, in the order of kSnapshotFields. Positions are
/// the geometry (dataset "position", N×3) and not repeated here.
inline const std::vector<XdmfField>& xdmf_particle_fields() {
  static const std::vector<XdmfField> fields = {
      {kSnapshotFields[0], "Scalar", "Float", 0, 1}, {kSnapshotFields[1], "Vector", "Float", 0, 3},
      {kSnapshotFields[2], "Vector", "Float", 0, 3}, {kSnapshotFields[3], "Vector", "Float", 0, 3},
      {kSnapshotFields[4], "Scalar", "UInt", 4, 1},  {kSnapshotFields[5], "Scalar", "UInt", 8, 1},
  };
  return fields;
}

/// Bytes per value of a real-valued particle dataset of `snapshot`.
inline int real_precision(const XdmfSnapshot& snapshot) {
  return snapshot.layout.single_precision ? 4 : 8;
}

/// The optional attribute of snapshots written with the rank field: the MPI rank that owned
/// each particle when the snapshot was written.
inline const XdmfField& xdmf_rank_field() {
  static const XdmfField field = {"rank", "Scalar", "UInt", 4, 1};
  return field;
}

namespace xdmf_detail {

/// Text safe inside an XML attribute value or element.
inline std::string escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '"')
      out += "&quot;";
    else if (c == '\'')
      out += "&apos;";
    else
      out += c;
  }
  return out;
}

inline std::string dimensions(std::uint64_t count, int components) {
  return std::to_string(count) + (components > 1 ? " " + std::to_string(components) : "");
}

/// A DataItem reading `rows` × `components` values of `dataset` (a path inside h5_file).
inline std::string hdf_item(const std::string& h5_file, const std::string& dataset,
                            const char* number_type, int precision, std::uint64_t rows,
                            int components) {
  return std::string("<DataItem Format=\"HDF\" NumberType=\"") + number_type + "\" Precision=\"" +
         std::to_string(precision) + "\" Dimensions=\"" + dimensions(rows, components) + "\">" +
         escape(h5_file) + ":/" + escape(dataset) + "</DataItem>";
}

inline std::string data_item(const XdmfSnapshot& snapshot, const char* dataset,
                             const char* number_type, int precision, int components) {
  return hdf_item(snapshot.h5_file, dataset, number_type, precision, snapshot.count, components);
}

/// An Attribute element centred on `center` ("Node" or "Cell") around the DataItem `item`.
inline std::string attribute_element(const std::string& name, const char* attribute_type,
                                     const char* center, const std::string& item) {
  return "        <Attribute Name=\"" + escape(name) + "\" AttributeType=\"" + attribute_type +
         "\" Center=\"" + center + "\">\n          " + item + "\n        </Attribute>\n";
}

inline std::string attribute(const XdmfSnapshot& snapshot, const XdmfField& field) {
  const bool real = std::string(field.number_type) == "Float";
  return attribute_element(
      field.name, field.attribute_type, "Node",
      data_item(snapshot, field.name, field.number_type,
                real ? real_precision(snapshot) : field.precision, field.components));
}

/// The file name without its extension: the name of that snapshot's grid.
inline std::string stem(const std::string& file) { return file.substr(0, file.rfind('.')); }

inline std::string uniform_grid(const XdmfSnapshot& snapshot) {
  const std::string n = std::to_string(snapshot.count);
  std::string grid =
      "      <Grid Name=\"" + escape(stem(snapshot.h5_file)) + "\" GridType=\"Uniform\">\n";
  grid += "        <Time Value=\"" + exact_decimal(snapshot.time) + "\"/>\n";
  const int index_bytes = snapshot.count > 0xffffffffull ? 8 : 4;
  grid += "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + n +
          "\" NodesPerElement=\"1\">\n          " +
          data_item(snapshot, "connectivity", "UInt", index_bytes, 1) + "\n        </Topology>\n";
  grid += "        <Geometry GeometryType=\"XYZ\">\n          " +
          data_item(snapshot, "position", "Float", real_precision(snapshot), 3) +
          "\n        </Geometry>\n";
  const std::vector<XdmfField>& fields = xdmf_particle_fields();
  for (std::size_t k = 0; k < fields.size(); ++k)
    if ((snapshot.layout.fields >> k) & 1u) grid += attribute(snapshot, fields[k]);
  if (snapshot.layout.rank_field) grid += attribute(snapshot, xdmf_rank_field());
  return grid + "      </Grid>\n";
}

/// The Triangle grid of `mesh` in one snapshot file: geometry `vertices`, topology `triangles`
/// and the per-triangle (Cell) attributes `force` and `pressure` of group `/mesh/<name>/`.
inline std::string mesh_grid(const XdmfSnapshot& snapshot, const XdmfMesh& mesh) {
  const std::string group = "mesh/" + mesh.name + "/";
  const std::string& file = snapshot.h5_file;
  const std::uint64_t t = mesh.triangle_count;
  std::string grid = "      <Grid Name=\"" + escape(stem(file)) + "\" GridType=\"Uniform\">\n";
  grid += "        <Time Value=\"" + exact_decimal(snapshot.time) + "\"/>\n";
  grid += "        <Topology TopologyType=\"Triangle\" NumberOfElements=\"" + std::to_string(t) +
          "\">\n          " + hdf_item(file, group + "triangles", "UInt", 4, t, 3) +
          "\n        </Topology>\n";
  grid += "        <Geometry GeometryType=\"XYZ\">\n          " +
          hdf_item(file, group + "vertices", "Float", 8, mesh.vertex_count, 3) +
          "\n        </Geometry>\n";
  grid += attribute_element("force", "Vector", "Cell",
                            hdf_item(file, group + "force", "Float", 8, t, 3));
  grid += attribute_element("pressure", "Scalar", "Cell",
                            hdf_item(file, group + "pressure", "Float", 8, t, 1));
  return grid + "      </Grid>\n";
}

/// The Polyline grid of the bonds in one snapshot file: one two-point cell per bond, geometry
/// `points`, topology `connectivity` and the per-bond (Cell) attributes `normal_force` and
/// `strength_used` of group `/bonds/`.
inline std::string bond_grid(const XdmfSnapshot& snapshot) {
  const std::string& file = snapshot.h5_file;
  const std::uint64_t b = snapshot.bond_count;
  std::string grid = "      <Grid Name=\"" + escape(stem(file)) + "\" GridType=\"Uniform\">\n";
  grid += "        <Time Value=\"" + exact_decimal(snapshot.time) + "\"/>\n";
  grid += "        <Topology TopologyType=\"Polyline\" NumberOfElements=\"" + std::to_string(b) +
          "\" NodesPerElement=\"2\">\n          " +
          hdf_item(file, "bonds/connectivity", "UInt", 8, b, 2) + "\n        </Topology>\n";
  grid += "        <Geometry GeometryType=\"XYZ\">\n          " +
          hdf_item(file, "bonds/points", "Float", 8, 2 * b, 3) + "\n        </Geometry>\n";
  for (const char* name : {"normal_force", "strength_used"})
    grid += attribute_element(name, "Scalar", "Cell",
                              hdf_item(file, std::string("bonds/") + name, "Float", 8, b, 1));
  return grid + "      </Grid>\n";
}

/// A whole .xmf text: a temporal collection named `name` around `grids`.
inline std::string temporal_collection(const std::string& name, const std::string& grids) {
  std::string text = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
  text += "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n  <Domain>\n";
  text += "    <Grid Name=\"" + escape(name) +
          "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  return text + grids + "    </Grid>\n  </Domain>\n</Xdmf>\n";
}

}  // namespace xdmf_detail

/// The whole .xmf text: a temporal collection named `name` with one uniform grid per snapshot,
/// in the order given, each named after its file.
inline std::string particle_xdmf(const std::string& name,
                                 const std::vector<XdmfSnapshot>& snapshots) {
  std::string grids;
  for (const XdmfSnapshot& snapshot : snapshots) grids += xdmf_detail::uniform_grid(snapshot);
  return xdmf_detail::temporal_collection(name, grids);
}

/// The .xmf text of the bonds: a temporal collection "bonds" with one Polyline grid per
/// snapshot, in the order given.
inline std::string bond_xdmf(const std::vector<XdmfSnapshot>& snapshots) {
  std::string grids;
  for (const XdmfSnapshot& snapshot : snapshots) grids += xdmf_detail::bond_grid(snapshot);
  return xdmf_detail::temporal_collection("bonds", grids);
}

/// The .xmf text of one mesh wall: a temporal collection named after the mesh with one
/// Triangle grid per snapshot, in the order given, each named after its file.
inline std::string mesh_xdmf(const XdmfMesh& mesh, const std::vector<XdmfSnapshot>& snapshots) {
  std::string grids;
  for (const XdmfSnapshot& snapshot : snapshots) grids += xdmf_detail::mesh_grid(snapshot, mesh);
  return xdmf_detail::temporal_collection(mesh.name, grids);
}

}  // namespace gpudem
