// The (s, t) grid shared by both synthetic occlusal surfaces: its resolution from the triangle
// budget, its vertices in L, the jaws' design heights sampled on it, and its triangulation.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

constexpr int kMinCells = 4;

/// ns for a given nt so that the slab's triangle count is closest to `budget`.
int ColumnsFor(std::size_t budget, int nt) {
  // SlabTriangleCount = 2 ns nt + 6 ns + 6 nt - 2 = ns (2 nt + 6) + 6 nt - 2.
  const double ns = (static_cast<double>(budget) + 2.0 - 6.0 * nt) / (2.0 * nt + 6.0);
  return std::max(kMinCells, static_cast<int>(std::lround(ns)));
}

}  // namespace

std::size_t SlabTriangleCount(int ns, int nt) {
  // Occlusal 2 ns nt; walls 2 per boundary edge: 4 (ns + nt); back: 2 per inner column and a
  // fan of nt + 1 in each end column: 2 (ns - 2) + 2 (nt + 1).
  const auto s = static_cast<std::size_t>(ns);
  const auto t = static_cast<std::size_t>(nt);
  return 2 * s * t + 6 * s + 6 * t - 2;
}

OcclusalGrid MakeOcclusalGrid(const DentitionLayout& layout, std::size_t triangle_budget) {
  const double length_s = layout.s_max - layout.s_min;
  const double length_t = layout.t_max - layout.t_min;
  // Square cells on the arch curve: ns / nt = length_s / length_t and 2 ns nt ~ budget.
  const auto nt_guess = static_cast<int>(
      std::lround(std::sqrt(static_cast<double>(triangle_budget) * length_t / (2.0 * length_s))));
  OcclusalGrid grid;
  std::size_t best_error = 0;
  for (int nt = std::max(kMinCells, nt_guess - 2); nt <= std::max(kMinCells, nt_guess + 2); ++nt) {
    const int ns = ColumnsFor(triangle_budget, nt);
    const std::size_t count = SlabTriangleCount(ns, nt);
    const std::size_t error =
        count > triangle_budget ? count - triangle_budget : triangle_budget - count;
    if (grid.nt == 0 || error < best_error) {
      best_error = error;
      grid.ns = ns;
      grid.nt = nt;
    }
  }
  grid.s0 = layout.s_min;
  grid.ds = length_s / grid.ns;
  grid.t0 = layout.t_min;
  grid.dt = length_t / grid.nt;
  grid.max_curvature = MaxArchCurvature(layout.arch);
  grid.xz.resize(static_cast<std::size_t>((grid.ns + 1) * (grid.nt + 1)));
  for (int i = 0; i <= grid.ns; ++i) {
    const Eigen::Vector2d c = ArchPoint(layout.arch, grid.S(i));
    const Eigen::Vector2d n = ArchNormal(layout.arch, grid.S(i));
    for (int j = 0; j <= grid.nt; ++j) grid.xz[grid.Index(i, j)] = c + grid.T(j) * n;
  }
  return grid;
}

OcclusalFields SampleFields(const DentitionLayout& layout, const OcclusalGrid& grid) {
  OcclusalFields f;
  const std::size_t n = grid.num_vertices();
  f.lower_y.resize(n);
  f.upper_design_y.resize(n);
  f.lower_tooth.resize(n);
  f.upper_tooth.resize(n);
  for (int i = 0; i <= grid.ns; ++i) {
    for (int j = 0; j <= grid.nt; ++j) {
      const auto v = static_cast<std::size_t>(grid.Index(i, j));
      const CrownSample lower = SampleCrowns(layout.lower, grid.S(i), grid.T(j));
      const CrownSample upper = SampleCrowns(layout.upper, grid.S(i), grid.T(j));
      f.lower_y[v] = layout.lower.gingiva_y + lower.height;
      f.lower_tooth[v] = lower.tooth;
      f.upper_design_y[v] = layout.upper.gingiva_y - upper.height;
      f.upper_tooth[v] = upper.tooth;
    }
  }
  return f;
}

std::vector<Eigen::Vector3i> OcclusalTriangles(const OcclusalGrid& grid,
                                               const std::vector<double>& lower_y) {
  std::vector<Eigen::Vector3i> tris;
  tris.reserve(static_cast<std::size_t>(2 * grid.ns * grid.nt));
  for (int i = 0; i < grid.ns; ++i) {
    for (int j = 0; j < grid.nt; ++j) {
      const int v00 = grid.Index(i, j), v10 = grid.Index(i + 1, j);
      const int v01 = grid.Index(i, j + 1), v11 = grid.Index(i + 1, j + 1);
      const auto y = [&](int v) { return lower_y[static_cast<std::size_t>(v)]; };
      // (s, t) -> (x, z) maps the frame (ds, dt) to (T, N) with T x N = -y, so triangles
      // clockwise in (s, t) face +y.
      if (std::abs(y(v00) - y(v11)) <= std::abs(y(v10) - y(v01))) {
        tris.emplace_back(v00, v01, v11);
        tris.emplace_back(v00, v11, v10);
      } else {
        tris.emplace_back(v00, v01, v10);
        tris.emplace_back(v10, v01, v11);
      }
    }
  }
  return tris;
}

}  // namespace occlude::io::synthetic
