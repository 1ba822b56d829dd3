// Angle-weighted pseudo-normals (Baerentzen & Aanaes) for signing distances to
// open and multi-shell meshes, and the brute-force signed distance used as the
// tests' reference.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "occlude/collision/closest_point.h"
#include "occlude/collision/signed_distance.h"

namespace occlude::collision {
namespace {

/// Unit normal (b - a) x (c - a), zero for a degenerate triangle.
Eigen::Vector3d UnitNormal(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

/// Angle (rad) between u and w; 0 when either is zero.
double Angle(const Eigen::Vector3d& u, const Eigen::Vector3d& w) {
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

/// Undirected edge key: smaller vertex index in the high half.
std::uint64_t EdgeKey(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return lo << 32 | hi;
}

}  // namespace

PseudoNormals::PseudoNormals(const io::TriangleMesh& mesh) {
  const std::size_t nt = mesh.num_triangles();
  std::vector<Eigen::Vector3d> face(nt);
  std::vector<Eigen::Vector3d> vertex(mesh.num_vertices(), Eigen::Vector3d::Zero());
  // (edge key, 3 t + k) for edge k (opposite corner k) of every triangle.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edge_slots(3 * nt);
  corners_ = mesh.triangles;
  for (std::size_t t = 0; t < nt; ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    face[t] = UnitNormal(mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2));
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& v = mesh.corner(t, k);
      const double angle = Angle(mesh.corner(t, (k + 1) % 3) - v, mesh.corner(t, (k + 2) % 3) - v);
      vertex[static_cast<std::size_t>(tri[k])] += angle * face[t];
      edge_slots[3 * t + static_cast<std::size_t>(k)] = {
          EdgeKey(tri[(k + 1) % 3], tri[(k + 2) % 3]), static_cast<std::uint32_t>(3 * t + k)};
    }
  }
  std::sort(edge_slots.begin(), edge_slots.end());
  edges_.resize(3 * nt);
  boundary_edge_.assign(3 * nt, false);
  boundary_vertex_.assign(mesh.num_vertices(), false);
  for (std::size_t i = 0; i < edge_slots.size();) {
    std::size_t j = i;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (; j < edge_slots.size() && edge_slots[j].first == edge_slots[i].first; ++j) {
      sum += face[edge_slots[j].second / 3];
    }
    if (j - i == 1) {  // a border edge: one face
      const std::uint32_t slot = edge_slots[i].second;
      boundary_edge_[slot] = true;
      const Eigen::Vector3i& tri = mesh.triangles[slot / 3];
      const int k = static_cast<int>(slot % 3);
      boundary_vertex_[static_cast<std::size_t>(tri[(k + 1) % 3])] = true;
      boundary_vertex_[static_cast<std::size_t>(tri[(k + 2) % 3])] = true;
    }
    for (; i < j; ++i) edges_[edge_slots[i].second] = sum.cast<float>();
  }
  faces_.reserve(nt);
  for (const auto& f : face) faces_.push_back(f.cast<float>());
  vertices_.reserve(vertex.size());
  for (const auto& v : vertex) vertices_.push_back(v.cast<float>());
}

Eigen::Vector3d PseudoNormals::At(std::uint32_t t, const Eigen::Vector3d& barycentric) const {
  int zeros = 0;
  int zero_k = 0;
  int max_k = 0;
  for (int k = 0; k < 3; ++k) {
    if (barycentric[k] < kZeroWeight) {
      ++zeros;
      zero_k = k;
    }
    if (barycentric[k] > barycentric[max_k]) max_k = k;
  }
  if (zeros >= 2) return Vertex(static_cast<std::uint32_t>(corners_[t][max_k]));
  if (zeros == 1) return Edge(t, zero_k);
  return Face(t);
}

bool PseudoNormals::OnBoundary(std::uint32_t t, const Eigen::Vector3d& barycentric) const {
  int zeros = 0, zero_k = 0, max_k = 0;
  for (int k = 0; k < 3; ++k) {
    if (barycentric[k] < kZeroWeight) {
      ++zeros;
      zero_k = k;
    }
    if (barycentric[k] > barycentric[max_k]) max_k = k;
  }
  if (zeros >= 2) return boundary_vertex_[static_cast<std::size_t>(corners_[t][max_k])];
  if (zeros == 1)
    return boundary_edge_[3 * static_cast<std::size_t>(t) + static_cast<std::size_t>(zero_k)];
  return false;
}

double PseudoNormals::Signed(std::uint32_t t, const Eigen::Vector3d& barycentric,
                             const Eigen::Vector3d& p, const Eigen::Vector3d& closest,
                             Eigen::Vector3d* unit_gradient) const {
  const Eigen::Vector3d n = At(t, barycentric);
  const Eigen::Vector3d diff = p - closest;
  const double sign = (diff.dot(n) >= 0.0 || OnBoundary(t, barycentric)) ? 1.0 : -1.0;
  const double dist = diff.norm();
  if (unit_gradient)
    *unit_gradient = dist > 0.0 ? Eigen::Vector3d(sign * diff / dist) : n.normalized();
  return sign * dist;
}

std::size_t PseudoNormals::MemoryBytes() const {
  return (faces_.capacity() + edges_.capacity() + vertices_.capacity()) * sizeof(Eigen::Vector3f) +
         corners_.capacity() * sizeof(Eigen::Vector3i) +
         (boundary_edge_.capacity() + boundary_vertex_.capacity()) / 8;
}

bool SignedDistanceBruteForce(const io::TriangleMesh& mesh, const PseudoNormals& normals,
                              const Eigen::Vector3d& p_F, SignedDistanceSample* out) {
  if (mesh.empty()) return false;
  TrianglePoint best;
  best.squared_distance = std::numeric_limits<double>::infinity();
  std::uint32_t best_t = 0;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const TrianglePoint tp =
        ClosestPointOnTriangle(p_F, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2));
    if (tp.squared_distance < best.squared_distance) {
      best = tp;
      best_t = static_cast<std::uint32_t>(t);
    }
  }
  out->distance = normals.Signed(best_t, best.barycentric, p_F, best.point, &out->normal);
  out->closest = best.point;
  out->triangle = best_t;
  return true;
}

}  // namespace occlude::collision
