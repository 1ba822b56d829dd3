// Coloured meshes for other tools: PLY with a colour and a signed distance per
// vertex, as MeshLab, CloudCompare, 3D Slicer and Blender read it.
//
// The layout (the property order these tools expect):
//   element vertex N: float x, y, z (mm, the mesh's frame); uchar red, green,
//     blue; float distance_mm (the caller's per-vertex scalar, e.g. the signed
//     distance to the opposing arch, negative = penetration)
//   element face M: list uchar int vertex_indices (the mesh's corner order)
// Binary little-endian by default, ASCII on request. Written atomically like
// the STL writers (mesh_io.h): never a half-written file.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::io {

using Rgb8 = std::array<std::uint8_t, 3>;

/// What each vertex of the mesh carries into the file, one entry per vertex.
struct VertexValues {
  std::vector<Rgb8> rgb;
  std::vector<float> distance_mm;  ///< finite; the caller's "far" sentinel is written as is
};

enum class PlyEncoding { kBinaryLittleEndian, kAscii };

/// Writes `mesh` with `values` as PLY. Throws MeshError naming `file` (folder
/// missing or not writable, empty or inconsistent mesh, a value count that is
/// not the vertex count, non-finite coordinates or distances, coordinates out of
/// float range).
void WriteColouredPly(const TriangleMesh& mesh, const VertexValues& values,
                      const std::filesystem::path& file,
                      PlyEncoding encoding = PlyEncoding::kBinaryLittleEndian);

}  // namespace occlude::io
