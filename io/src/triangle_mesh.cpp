// TriangleMesh geometry helpers (bounds, area, normals, transforms, concatenation).
#include "occlude/io/triangle_mesh.h"

#include <sstream>

namespace occlude::io {

Eigen::AlignedBox3d TriangleMesh::Bounds() const {
  Eigen::AlignedBox3d box;  // constructed empty
  for (const auto& v : vertices) box.extend(v);
  return box;
}

double TriangleMesh::SurfaceArea() const {
  double area = 0.0;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    area += 0.5 * (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0)).norm();
  }
  return area;
}

void TriangleMesh::ComputeFaceNormals() {
  face_normals.resize(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Eigen::Vector3d n = (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0));
    const double len = n.norm();
    face_normals[t] = len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
  }
}

TriangleMesh TriangleMesh::Transformed(const Eigen::Isometry3d& X_GF) const {
  TriangleMesh out = *this;
  for (auto& v : out.vertices) v = X_GF * v;
  for (auto& n : out.face_normals) n = X_GF.linear() * n;
  return out;
}

void TriangleMesh::Append(const TriangleMesh& other) {
  const auto vertex_offset = static_cast<int>(vertices.size());
  const auto part_offset = static_cast<std::int32_t>(parts.size());
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  for (const auto& tri : other.triangles) {
    triangles.push_back(tri + Eigen::Vector3i::Constant(vertex_offset));
  }
  face_normals.insert(face_normals.end(), other.face_normals.begin(), other.face_normals.end());
  for (const auto p : other.triangle_part) triangle_part.push_back(p + part_offset);
  parts.insert(parts.end(), other.parts.begin(), other.parts.end());
}

std::string TriangleMesh::ConsistencyError() const {
  std::ostringstream err;
  if (face_normals.size() != triangles.size()) {
    err << "face_normals has " << face_normals.size() << " entries for " << triangles.size()
        << " triangles";
  } else if (triangle_part.size() != triangles.size()) {
    err << "triangle_part has " << triangle_part.size() << " entries for " << triangles.size()
        << " triangles";
  } else if (!triangles.empty() && parts.empty()) {
    err << "a non-empty mesh has no parts";
  } else {
    const auto nv = static_cast<int>(vertices.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      if ((triangles[t].array() < 0).any() || (triangles[t].array() >= nv).any()) {
        err << "triangle " << t << " indexes a vertex outside 0.." << nv - 1;
        break;
      }
      if (triangle_part[t] < 0 || triangle_part[t] >= static_cast<std::int32_t>(parts.size())) {
        err << "triangle " << t << " names part " << triangle_part[t] << " of " << parts.size();
        break;
      }
    }
  }
  return err.str();
}

}  // namespace occlude::io
