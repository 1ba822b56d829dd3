// Rasterization of the top envelope (height_map.h): each triangle's footprint is scanned over
// the cell centres it covers (barycentric test in the plane), keeping the highest point.
#include "height_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace occlude::analysis {
namespace {

// Writes the triangle's height at every cell centre inside its footprint.
void ScanTriangle(const Eigen::Vector3d (&p)[3], std::int32_t t, HeightMap* map) {
  const Eigen::Vector2d a = p[0].head<2>(), b = p[1].head<2>(), c = p[2].head<2>();
  const double det = (b - a).x() * (c - a).y() - (c - a).x() * (b - a).y();
  if (std::abs(det) < 1e-14) return;  // seen edge-on: its neighbours cover the cells
  const Eigen::Vector2d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
  const auto cell_of = [&](double v, double corner) {
    return static_cast<int>(std::floor((v - corner) / map->cell - 0.5));
  };
  const int i0 = std::max(0, cell_of(lo.x(), map->corner.x()) + 1);
  const int i1 = std::min(map->nx - 1, cell_of(hi.x(), map->corner.x()));
  const int j0 = std::max(0, cell_of(lo.y(), map->corner.y()) + 1);
  const int j1 = std::min(map->ny - 1, cell_of(hi.y(), map->corner.y()));
  // Along a row (fixed y) each barycentric weight is affine in x: l = (sx x + sy y + s0) / det,
  // with (sx, sy, s0) below for l1 and l2 (l3 = 1 - l1 - l2). Each row scans the cells between
  // where the three are >= -1e-9 (far beyond their rounding), widened by a cell each way; the
  // exact test below decides, so the map is the same as from scanning the whole box.
  const double w1[3] = {b.y() - c.y(), c.x() - b.x(), b.x() * c.y() - c.x() * b.y()};
  const double w2[3] = {c.y() - a.y(), a.x() - c.x(), c.x() * a.y() - a.x() * c.y()};
  const double w3[3] = {-(w1[0] + w2[0]), -(w1[1] + w2[1]), det - w1[2] - w2[2]};
  for (int j = j0; j <= j1; ++j) {
    const double y = map->corner.y() + map->cell * (j + 0.5);
    double from = -std::numeric_limits<double>::infinity(), to = -from;
    bool empty = false;
    for (const double* w : {w1, w2, w3}) {
      const double slope = w[0] / det, rest = (w[1] * y + w[2]) / det + 1e-9;
      if (slope > 0) {
        from = std::max(from, -rest / slope);
      } else if (slope < 0) {
        to = std::min(to, -rest / slope);
      } else if (rest < 0) {
        empty = true;
      }
    }
    if (empty || from > to) continue;
    const double first = std::ceil((from - map->corner.x()) / map->cell - 0.5) - 1.0;
    const double last = std::floor((to - map->corner.x()) / map->cell - 0.5) + 1.0;
    const int is = first > i0 ? static_cast<int>(std::min<double>(first, i1 + 1)) : i0;
    const int ie = last < i1 ? static_cast<int>(std::max<double>(last, i0 - 1)) : i1;
    for (int i = is; i <= ie; ++i) {
      const Eigen::Vector2d q = map->corner + map->cell * Eigen::Vector2d(i + 0.5, j + 0.5);
      const double l1 = ((b - q).x() * (c - q).y() - (c - q).x() * (b - q).y()) / det;
      const double l2 = ((c - q).x() * (a - q).y() - (a - q).x() * (c - q).y()) / det;
      const double l3 = 1.0 - l1 - l2;
      if (l1 < 0.0 || l2 < 0.0 || l3 < 0.0) continue;
      const double h = l1 * p[0].z() + l2 * p[1].z() + l3 * p[2].z();
      const auto k = static_cast<std::size_t>(map->Index(i, j));
      if (std::isnan(map->height[k]) || h > map->height[k]) {
        map->height[k] = h;
        map->triangle[k] = t;
      }
    }
  }
}

}  // namespace

std::vector<double> MaxFilter(const HeightMap& map, double radius_mm) {
  const int r = std::max(0, static_cast<int>(std::lround(radius_mm / map.cell)));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto pass = [&](const std::vector<double>& in, bool along_x) {
    std::vector<double> out(in.size(), nan);
    const int n = along_x ? map.nx : map.ny, lines = along_x ? map.ny : map.nx;
    for (int line = 0; line < lines; ++line) {
      for (int k = 0; k < n; ++k) {
        double best = nan;
        for (int d = std::max(0, k - r); d <= std::min(n - 1, k + r); ++d) {
          const double h =
              in[static_cast<std::size_t>(along_x ? map.Index(d, line) : map.Index(line, d))];
          if (!std::isnan(h) && (std::isnan(best) || h > best)) best = h;
        }
        out[static_cast<std::size_t>(along_x ? map.Index(k, line) : map.Index(line, k))] = best;
      }
    }
    return out;
  };
  return pass(pass(map.height, true), false);
}

std::vector<double> CrownWeights(const HeightMap& map, double floor, double below_top_mm,
                                 double radius_mm) {
  const std::vector<double> top = MaxFilter(map, radius_mm);
  std::vector<double> weight(map.height.size(), 0.0);
  for (std::size_t c = 0; c < weight.size(); ++c) {
    const double h = map.height[c], above = h - (top[c] - below_top_mm);
    if (!std::isnan(h) && h >= floor && above > 0.0) weight[c] = above * above;
  }
  return weight;
}

ViewAxes AxesAround(const Eigen::Vector3d& origin_J, const Eigen::Vector3d& up_J) {
  ViewAxes axes;
  axes.origin_J = origin_J;
  axes.up_J = up_J.normalized();
  const Eigen::Vector3d seed =
      std::abs(axes.up_J.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  axes.e1_J = (seed - seed.dot(axes.up_J) * axes.up_J).normalized();
  axes.e2_J = axes.up_J.cross(axes.e1_J);
  return axes;
}

int HeightMap::CellAt(const Eigen::Vector2d& q) const {
  const auto i = static_cast<int>(std::floor((q.x() - corner.x()) / cell));
  const auto j = static_cast<int>(std::floor((q.y() - corner.y()) / cell));
  return (i < 0 || j < 0 || i >= nx || j >= ny) ? -1 : Index(i, j);
}

HeightMap RasterizeTop(const io::TriangleMesh& mesh, const std::vector<std::int32_t>& triangles,
                       const ViewAxes& axes, double cell) {
  HeightMap map;
  map.axes = axes;
  map.cell = cell;
  const std::size_t n = triangles.empty() ? mesh.num_triangles() : triangles.size();
  const auto tri_at = [&](std::size_t k) {
    return triangles.empty() ? static_cast<std::int32_t>(k) : triangles[k];
  };
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (std::size_t k = 0; k < n; ++k) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2d q = axes.Plane(mesh.corner(static_cast<std::size_t>(tri_at(k)), c));
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  }
  if (n == 0) return map;
  map.corner = lo - Eigen::Vector2d::Constant(cell);
  map.nx = static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)) + 2;
  map.ny = static_cast<int>(std::ceil((hi.y() - lo.y()) / cell)) + 2;
  const auto cells = static_cast<std::size_t>(map.nx) * static_cast<std::size_t>(map.ny);
  map.height.assign(cells, std::numeric_limits<double>::quiet_NaN());
  map.triangle.assign(cells, -1);
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t t = tri_at(k);
    Eigen::Vector3d p[3];
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = mesh.corner(static_cast<std::size_t>(t), c);
      p[c] << axes.Plane(v), axes.Height(v);
    }
    ScanTriangle(p, t, &map);
  }
  return map;
}

}  // namespace occlude::analysis
