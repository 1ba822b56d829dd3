// One fuzz input through io::LoadMeshFromBytes as the named file type, then the
// loader's contract checked: a MeshError is the only way to fail, and a mesh
// that loads has indices in range, finite vertices, no zero-area triangle and
// one part covering every triangle. A broken contract traps, so libFuzzer
// reports it like a crash.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "occlude/io/mesh_io.h"

namespace occlude::fuzz {

inline void Require(bool condition) {
  if (!condition) __builtin_trap();
}

inline int FuzzMesh(const std::uint8_t* data, std::size_t size, const char* name) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  io::TriangleMesh mesh;
  try {
    mesh = io::LoadMeshFromBytes(bytes, name);
  } catch (const io::MeshError&) {
    return 0;  // rejected with a message: fine
  }
  Require(!mesh.triangles.empty());
  const auto vertices = static_cast<int>(mesh.vertices.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    Require((t.array() >= 0).all() && (t.array() < vertices).all());
    const Eigen::Vector3d a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    Require((b - a).cross(c - a).squaredNorm() > 0.0);
  }
  for (const Eigen::Vector3d& v : mesh.vertices) Require(v.allFinite());
  Require(mesh.parts.size() == 1 && mesh.triangle_part.size() == mesh.triangles.size());
  Require(mesh.face_normals.size() == mesh.triangles.size());
  return 0;
}

}  // namespace occlude::fuzz
