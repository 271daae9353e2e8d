#pragma once
/// STL triangle meshes (ASCII and binary) for walls and tools: reading, placement, welding.
#include <array>
#include <string>
#include <vector>

#include "core/TriangleMesh.hpp"
#include "core/Vec3.hpp"

namespace gpudem {

/// Where a mesh goes in the scene: p' = R(rotation_axis, rotation_angle) (scale · p) + offset,
/// R the right-handed rotation about the axis through the origin (Rodrigues' formula).
struct MeshPlacement {
  double scale = 1;
  Vec3 offset;
  Vec3 rotation_axis{0, 0, 1};
  double rotation_angle = 0;  ///< radians
};

/// The triangles of the STL file `path` as written, three corners each (facet normals are
/// ignored: the corner order gives the orientation).
///
/// A file whose size is 84 + 50 · (the uint32 at byte 80) is binary: an 80-byte header, the
/// triangle count, then per triangle a normal and three corners as little-endian float32 and
/// a uint16 attribute. Otherwise a file that starts with "solid" and holds no NUL byte is
/// ASCII: one or more `solid NAME ... endsolid NAME` blocks of `facet normal nx ny nz /
/// outer loop / vertex x y z (three times) / endloop / endfacet`, keywords in any case, tokens
/// separated by any white space, the rest of a `solid` or `endsolid` line being the name. Any
/// other file is a binary file of the wrong size.
///
/// Throws InputError (file, line for ASCII, triangle number) for a missing or unreadable file,
/// a truncated binary file or one with trailing bytes, an unexpected ASCII token, a
/// non-finite coordinate or a file with no triangle.
std::vector<std::array<Vec3, 3>> read_stl(const std::string& path);

/// The mesh of the STL file `path`, moved by `placement` and then welded by build_mesh.
/// Throws InputError for the errors of read_stl, a scale that is not positive and finite, a
/// zero or non-finite rotation axis, a non-finite angle or offset, a placed coordinate that
/// overflows, and a file whose triangles all have zero area.
TriangleMesh load_mesh(const std::string& path, const MeshPlacement& placement);

}  // namespace gpudem
