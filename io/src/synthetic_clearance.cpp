// Clearance of the synthetic bite: the vertical gap the upper surface needs over each vertex of
// the lower one so that pulling the jaws kPullApart apart along the occlusal axis leaves them
// at least kKeptApart apart (see synthetic_jaws_internal.h). Two sampled estimates with a
// margin (the slope of the triangles around a vertex; the rise of the lower surface beside
// it) and an exact point-to-surface distance for the few contact vertices.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

/// The sampled estimates aim this much beyond kKeptApart: they see vertices and planes, not
/// every point of the neighbouring triangles.
constexpr double kSampledKeptApart = kKeptApart + 0.02;  // mm

Eigen::Vector3d Point3(const OcclusalGrid& grid, const std::vector<double>& y, int v) {
  const Eigen::Vector2d& xz = grid.xz[static_cast<std::size_t>(v)];
  return Eigen::Vector3d(xz.x(), y[static_cast<std::size_t>(v)], xz.y());
}

double PointSegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double length2 = ab.squaredNorm();
  const double u = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + u * ab)).norm();
}

/// Distance from p to the closed triangle (a, b, c): to its plane when p projects inside it,
/// else to the nearest edge. (io does not depend on collision, which has the general one.)
double PointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (n2 > 0.0) {
    const Eigen::Vector3d q = p - ((p - a).dot(n) / n2) * n;
    if ((b - a).cross(q - a).dot(n) >= 0.0 && (c - b).cross(q - b).dot(n) >= 0.0 &&
        (a - c).cross(q - c).dot(n) >= 0.0) {
      return (p - q).norm();
    }
  }
  return std::min({PointSegmentDistance(p, a, b), PointSegmentDistance(p, b, c),
                   PointSegmentDistance(p, c, a)});
}

/// False when the bounding box of grid cell (ci, cj) with heights y is farther than `radius`
/// from p (then neither of its triangles is closer).
bool CellMayBeWithin(const OcclusalGrid& grid, const std::vector<double>& y, int ci, int cj,
                     const Eigen::Vector3d& p, double radius) {
  Eigen::AlignedBox3d box;
  for (const int v : {grid.Index(ci, cj), grid.Index(ci + 1, cj), grid.Index(ci, cj + 1),
                      grid.Index(ci + 1, cj + 1)}) {
    box.extend(Point3(grid, y, v));
  }
  return box.squaredExteriorDistance(p) <= radius * radius;
}

/// Largest lower height within a square window covering the kKeptApart disc of each vertex
/// (separable running maximum).
std::vector<double> WindowMaximum(const OcclusalGrid& grid, const std::vector<double>& y) {
  const int dj = static_cast<int>(std::ceil(kKeptApart / grid.dt));
  std::vector<double> along_t(y.size());
  for (int i = 0; i <= grid.ns; ++i) {
    for (int j = 0; j <= grid.nt; ++j) {
      double m = y[static_cast<std::size_t>(grid.Index(i, j))];
      for (int b = std::max(0, j - dj); b <= std::min(grid.nt, j + dj); ++b) {
        m = std::max(m, y[static_cast<std::size_t>(grid.Index(i, b))]);
      }
      along_t[static_cast<std::size_t>(grid.Index(i, j))] = m;
    }
  }
  std::vector<double> window(y.size());
  for (int j = 0; j <= grid.nt; ++j) {
    const double stretch = 1.0 + std::min(grid.T(j) - kKeptApart, 0.0) * grid.max_curvature;
    const int di = static_cast<int>(std::ceil(kKeptApart / (grid.ds * stretch))) + 1;
    for (int i = 0; i <= grid.ns; ++i) {
      double m = along_t[static_cast<std::size_t>(grid.Index(i, j))];
      for (int a = std::max(0, i - di); a <= std::min(grid.ns, i + di); ++a) {
        m = std::max(m, along_t[static_cast<std::size_t>(grid.Index(a, j))]);
      }
      window[static_cast<std::size_t>(grid.Index(i, j))] = m;
    }
  }
  return window;
}

}  // namespace

double TriangleClearance(const OcclusalGrid& grid, const std::vector<double>& y,
                         const Eigen::Vector3i& tri) {
  const Eigen::Vector3d a = Point3(grid, y, tri[0]);
  const Eigen::Vector3d n = (Point3(grid, y, tri[1]) - a).cross(Point3(grid, y, tri[2]) - a);
  return std::max(0.0, kSampledKeptApart * n.norm() / std::abs(n.y()) - kPullApart);
}

std::vector<double> SlopeClearance(const OcclusalGrid& grid, const std::vector<double>& lower_y,
                                   const std::vector<Eigen::Vector3i>& triangles) {
  std::vector<double> clearance(grid.num_vertices(), 0.0);
  for (const Eigen::Vector3i& tri : triangles) {
    const double d = TriangleClearance(grid, lower_y, tri);
    for (int k = 0; k < 3; ++k) {
      double& c = clearance[static_cast<std::size_t>(tri[k])];
      c = std::max(c, d);
    }
  }
  return clearance;
}

std::vector<double> RiseClearance(const OcclusalGrid& grid, const std::vector<double>& lower_y,
                                  const std::vector<double>& known_gap) {
  const std::vector<double> window = WindowMaximum(grid, lower_y);
  const double r = kSampledKeptApart;
  std::vector<double> clearance(grid.num_vertices(), 0.0);
  for (int i = 0; i <= grid.ns; ++i) {
    for (int j = 0; j <= grid.nt; ++j) {
      const auto v = static_cast<std::size_t>(grid.Index(i, j));
      const double base = lower_y[v] + kPullApart;
      // sqrt(r^2 - h^2) <= r: nothing to do where even the highest neighbour cannot beat the
      // gap the vertex has anyway.
      if (window[v] - base + r <= std::max(0.0, known_gap[v])) continue;
      double need = 0.0;
      ForGridVerticesNear(grid, grid.xz[v], grid.S(i), grid.T(j), r, [&](int z, double h) {
        const double rise = lower_y[static_cast<std::size_t>(z)] - base;
        if (rise + r <= need) return;
        need = std::max(need, rise + std::sqrt(std::max(0.0, r * r - h * h)));
      });
      clearance[v] = need;
    }
  }
  return clearance;
}

double DistanceToSurfaceNear(const OcclusalGrid& grid, const std::vector<double>& y,
                             const std::vector<Eigen::Vector3i>& triangles, int v,
                             const Eigen::Vector3d& p, double radius) {
  // Every triangle within `radius` of p (which lies over vertex v) has a corner within
  // radius + its longest edge (a cell diagonal) of v in xz.
  const int i = v / (grid.nt + 1);
  const int j = v % (grid.nt + 1);
  const double reach = radius + CellDiagonal(grid);
  const double stretch = 1.0 + std::min(grid.T(j) - reach, 0.0) * grid.max_curvature;
  const int di = static_cast<int>(std::ceil(reach / (grid.ds * stretch))) + 1;
  const int dj = static_cast<int>(std::ceil(reach / grid.dt)) + 1;
  double nearest = radius;
  for (int ci = std::max(0, i - di); ci < std::min(grid.ns, i + di); ++ci) {
    for (int cj = std::max(0, j - dj); cj < std::min(grid.nt, j + dj); ++cj) {
      if (!CellMayBeWithin(grid, y, ci, cj, p, nearest)) continue;
      for (int k = 0; k < 2; ++k) {
        const Eigen::Vector3i& tri =
            triangles[static_cast<std::size_t>(2 * (ci * grid.nt + cj) + k)];
        nearest = std::min(
            nearest, PointTriangleDistance(p, Point3(grid, y, tri[0]), Point3(grid, y, tri[1]),
                                           Point3(grid, y, tri[2])));
      }
    }
  }
  return nearest;
}

}  // namespace occlude::io::synthetic
