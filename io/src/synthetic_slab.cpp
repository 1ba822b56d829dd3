// Closed "horseshoe slab" meshes of the synthetic jaws: the occlusal height field over the
// shared (s, t) grid, vertical walls along the grid boundary and a flat back. The solid is the
// vertical prism between the back and the height field over the grid's footprint, so the
// surface is closed, edge-manifold and embedded whenever the grid does not fold in xz and the
// back lies beyond every occlusal height.
#include <utility>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

/// The grid boundary as a closed vertex loop, in the direction in which the occlusal
/// triangles of OcclusalTriangles (normal +y) traverse it: clockwise in (s, t).
std::vector<int> BoundaryLoop(const OcclusalGrid& g) {
  std::vector<int> loop;
  loop.reserve(static_cast<std::size_t>(2 * (g.ns + g.nt)));
  for (int i = g.ns; i >= 0; --i) loop.push_back(g.Index(i, 0));
  for (int j = 1; j <= g.nt; ++j) loop.push_back(g.Index(0, j));
  for (int i = 1; i <= g.ns; ++i) loop.push_back(g.Index(i, g.nt));
  for (int j = g.nt - 1; j >= 1; --j) loop.push_back(g.Index(g.ns, j));
  return loop;
}

/// Majority part of a triangle's corners; when all differ, the first tooth among them.
std::int32_t TrianglePart(const Eigen::Vector3i& tri, const std::vector<std::int32_t>& part) {
  const std::int32_t a = part[static_cast<std::size_t>(tri[0])];
  const std::int32_t b = part[static_cast<std::size_t>(tri[1])];
  const std::int32_t c = part[static_cast<std::size_t>(tri[2])];
  if (a == b || a == c) return a;
  if (b == c) return b;
  return a != 0 ? a : (b != 0 ? b : c);
}

/// Back triangles over the back copies `back` (indexed by grid vertex), oriented with normal
/// -y (counter-clockwise in (s, t)): two per inner column, a fan in each end column (whose
/// outer side carries nt + 1 collinear vertices).
void AddBack(const OcclusalGrid& g, const std::vector<int>& back,
             std::vector<Eigen::Vector3i>* tris) {
  const auto b = [&](int i, int j) { return back[static_cast<std::size_t>(g.Index(i, j))]; };
  tris->emplace_back(b(1, 0), b(1, g.nt), b(0, g.nt));
  for (int j = g.nt - 1; j >= 0; --j) tris->emplace_back(b(1, 0), b(0, j + 1), b(0, j));
  for (int i = 1; i + 1 < g.ns; ++i) {
    tris->emplace_back(b(i, 0), b(i + 1, 0), b(i + 1, g.nt));
    tris->emplace_back(b(i, 0), b(i + 1, g.nt), b(i, g.nt));
  }
  const int last = g.ns - 1;
  tris->emplace_back(b(last, g.nt), b(last, 0), b(g.ns, 0));
  for (int j = 0; j < g.nt; ++j) tris->emplace_back(b(last, g.nt), b(g.ns, j), b(g.ns, j + 1));
}

}  // namespace

TriangleMesh MakeSlab(const OcclusalGrid& grid, const std::vector<Eigen::Vector3i>& triangles,
                      const std::vector<double>& occlusal_y, double back_y, bool occlusal_faces_up,
                      const std::vector<std::int32_t>& vertex_part, std::vector<MeshPart> parts) {
  TriangleMesh mesh;
  const std::size_t n = grid.num_vertices();
  const std::vector<int> loop = BoundaryLoop(grid);
  mesh.vertices.reserve(n + loop.size());
  for (std::size_t v = 0; v < n; ++v) {
    mesh.vertices.emplace_back(grid.xz[v].x(), occlusal_y[v], grid.xz[v].y());
  }
  std::vector<int> back(n, -1);
  for (const int v : loop) {
    back[static_cast<std::size_t>(v)] = static_cast<int>(mesh.vertices.size());
    const Eigen::Vector2d& xz = grid.xz[static_cast<std::size_t>(v)];
    mesh.vertices.emplace_back(xz.x(), back_y, xz.y());
  }
  mesh.triangles = triangles;
  mesh.triangles.reserve(SlabTriangleCount(grid.ns, grid.nt));
  for (const Eigen::Vector3i& tri : triangles) {
    mesh.triangle_part.push_back(TrianglePart(tri, vertex_part));
  }
  // Walls: each boundary edge a -> b of the occlusal side is matched by b -> a in its wall quad.
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const int a = loop[k];
    const int b = loop[(k + 1) % loop.size()];
    const int a_back = back[static_cast<std::size_t>(a)];
    const int b_back = back[static_cast<std::size_t>(b)];
    mesh.triangles.emplace_back(b, a, a_back);
    mesh.triangles.emplace_back(b, a_back, b_back);
  }
  AddBack(grid, back, &mesh.triangles);
  mesh.triangle_part.resize(mesh.triangles.size(), 0);
  if (!occlusal_faces_up) {  // the solid lies above: every triangle turns round
    for (Eigen::Vector3i& tri : mesh.triangles) std::swap(tri[1], tri[2]);
  }
  mesh.parts = std::move(parts);
  mesh.ComputeFaceNormals();
  return mesh;
}

}  // namespace occlude::io::synthetic
