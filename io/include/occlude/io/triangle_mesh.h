// The project's own triangle mesh: what every module speaks.
//
// Conventions: coordinates in millimetres, in the frame F of the file the mesh
// came from (a jaw's own frame: L for the lower jaw, U for the upper jaw).
// Triangles are counter-clockwise when seen from outside, so a face normal
// (b - a) x (c - a) points outward. Vertices are welded (no duplicates).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace occlude::io {

/// One part of a jaw (a tooth, the gingiva/base, or the whole file).
struct MeshPart {
  std::string name;      ///< e.g. "Tooth_14" (file stem) or "synthetic tooth 14"
  int tooth_number = 0;  ///< Universal numbering 1..32; 0 = not a tooth / unknown
};

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;      ///< p_FV, mm
  std::vector<Eigen::Vector3i> triangles;     ///< vertex indices, CCW from outside
  std::vector<Eigen::Vector3d> face_normals;  ///< unit outward normal per triangle
  std::vector<std::int32_t> triangle_part;    ///< index into `parts`, per triangle
  std::vector<MeshPart> parts;                ///< at least one when non-empty

  std::size_t num_triangles() const { return triangles.size(); }
  std::size_t num_vertices() const { return vertices.size(); }
  bool empty() const { return triangles.empty(); }

  /// Corner k (0..2) of triangle t.
  const Eigen::Vector3d& corner(std::size_t t, int k) const {
    return vertices[static_cast<std::size_t>(triangles[t][k])];
  }

  /// Axis-aligned bounds of the vertices in F (empty box for an empty mesh).
  Eigen::AlignedBox3d Bounds() const;
  /// Total area in mm^2.
  double SurfaceArea() const;
  /// Recomputes `face_normals` from the corners (zero vector for a degenerate face).
  void ComputeFaceNormals();
  /// The same surface expressed in frame G, given X_GF (pose of F in G).
  TriangleMesh Transformed(const Eigen::Isometry3d& X_GF) const;
  /// Appends `other` as new parts (part indices are shifted; vertices are not welded
  /// across the two meshes).
  void Append(const TriangleMesh& other);
  /// Checks sizes and index ranges; returns an empty string when consistent,
  /// otherwise what is wrong.
  std::string ConsistencyError() const;
};

}  // namespace occlude::io
