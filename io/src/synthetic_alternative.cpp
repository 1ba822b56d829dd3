// The full-cusp Class II alternative of the synthetic bite: the upper jaw moved by
// kClass2ShiftMm along +z (anterior, upper mesial by a premolar width) must again lie on the
// lower without interpenetrating, so that maximum contact has a second, distinct seat there
// (clinical.md: "Why maximum contact alone is not the final occlusion"). The upper surface is
// lifted by E >= 0 where, so moved, it would dip into the lower (a second bite record, like the
// gap function's first): at the alternative it then rests on the lower exactly where E binds.
//
// The check runs at the vertices of both surfaces: each upper vertex moved by the shift lies at
// least kAlternativeMarginMm above the lower's triangles under it, and each lower vertex at least
// that far below the moved upper triangles over it (their corners lifted together where one is
// short). Between vertices the two piecewise-linear surfaces may still cross by a fraction of
// that: the alternative is a seat for the search, not an exact ground truth like the bite.
#include <algorithm>
#include <cmath>
#include <optional>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

constexpr double kAlternativeMarginMm = 0.02;
constexpr double kAlternativeSpotSpacingMm = 1.4;  // spots of the alternative's contact
constexpr double kSpotBindMm = 0.05;               // a spot's lift exceeds the other gaps by this
constexpr double kSpotLiftRatio = 4.0;             // the thinning stays below this times the lift

/// A point of the grid's xz footprint: an occlusal triangle and the barycentric weights there.
struct GridPoint {
  std::size_t triangle = 0;
  Eigen::Vector3d weight = Eigen::Vector3d::Zero();
};

/// Locates xz points in the occlusal triangulation through the grid's rows: row i is the line
/// C_i + t N_i, and (q - C_i) . T_i decreases along the rows wherever 1 + t kappa > 0, which
/// holds across the whole grid (it does not fold).
class GridLocator {
 public:
  GridLocator(const OcclusalGrid& grid, const std::vector<Eigen::Vector3i>& triangles)
      : grid_(grid), triangles_(triangles) {
    const double span = grid.T(grid.nt) - grid.T(0);
    for (int i = 0; i <= grid.ns; ++i) {
      const Eigen::Vector2d& a = grid.xz[static_cast<std::size_t>(grid.Index(i, 0))];
      const Eigen::Vector2d n =
          (grid.xz[static_cast<std::size_t>(grid.Index(i, grid.nt))] - a) / span;
      normal_.push_back(n);
      origin_.push_back(a - grid.T(0) * n);
    }
  }

  /// The triangle containing q, searched from row `hint`; nullopt outside the footprint.
  std::optional<GridPoint> Locate(const Eigen::Vector2d& q, int hint) const {
    const std::optional<int> row = Bracket(q, std::clamp(hint, 0, grid_.ns - 1));
    if (!row) return std::nullopt;
    const int i = *row;
    const double fa = Along(q, i), fb = Along(q, i + 1);
    const double lambda = fa / (fa - fb);
    const double t = (1.0 - lambda) * (q - origin_[i]).dot(normal_[i]) +
                     lambda * (q - origin_[i + 1]).dot(normal_[i + 1]);
    const int j = static_cast<int>(std::floor((t - grid_.t0) / grid_.dt));
    std::optional<GridPoint> best;
    double best_min = -1e-9;  // accept points on edges (rounding)
    for (int ci = std::max(0, i - 1); ci <= std::min(grid_.ns - 1, i + 1); ++ci) {
      for (int cj = std::max(0, j - 1); cj <= std::min(grid_.nt - 1, j + 1); ++cj) {
        for (int k = 0; k < 2; ++k) {
          const auto tri = static_cast<std::size_t>(2 * (ci * grid_.nt + cj) + k);
          const Eigen::Vector3d w = Barycentric(q, triangles_[tri]);
          if (w.minCoeff() > best_min) {
            best_min = w.minCoeff();
            best = GridPoint{tri, w};
          }
        }
      }
    }
    return best;
  }

 private:
  double Along(const Eigen::Vector2d& q, int i) const {
    const Eigen::Vector2d tangent(normal_[i].y(), -normal_[i].x());
    return (q - origin_[i]).dot(tangent);
  }

  /// The row i with Along(q, i) >= 0 > Along(q, i + 1), walking from `start`.
  std::optional<int> Bracket(const Eigen::Vector2d& q, int start) const {
    int i = start;
    for (int step = 0; step <= grid_.ns; ++step) {
      if (Along(q, i) < 0.0) {
        if (i == 0) return std::nullopt;
        --i;
      } else if (Along(q, i + 1) >= 0.0) {
        if (i + 1 == grid_.ns) return std::nullopt;
        ++i;
      } else {
        return i;
      }
    }
    return std::nullopt;
  }

  Eigen::Vector3d Barycentric(const Eigen::Vector2d& q, const Eigen::Vector3i& tri) const {
    const Eigen::Vector2d& a = grid_.xz[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector2d& b = grid_.xz[static_cast<std::size_t>(tri[1])];
    const Eigen::Vector2d& c = grid_.xz[static_cast<std::size_t>(tri[2])];
    const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
      return u.x() * v.y() - u.y() * v.x();
    };
    const double area = cross(b - a, c - a);
    const double wb = cross(q - a, c - a) / area;
    const double wc = cross(b - a, q - a) / area;
    return Eigen::Vector3d(1.0 - wb - wc, wb, wc);
  }

  const OcclusalGrid& grid_;
  const std::vector<Eigen::Vector3i>& triangles_;
  std::vector<Eigen::Vector2d> origin_, normal_;  // per row: C_i and N_i
};

/// The row where a point of row i lands after moving by `shift` along +z: on the straight
/// posterior segments the arch runs along -z on the left (s > 0) and +z on the right.
int ShiftedRowHint(const OcclusalGrid& grid, int i, double shift) {
  const int rows = static_cast<int>(std::lround(shift / grid.ds));
  return grid.S(i) > 0.0 ? i - rows : i + rows;
}

double Interpolate(const std::vector<double>& y, const Eigen::Vector3i& tri,
                   const Eigen::Vector3d& w) {
  return w[0] * y[static_cast<std::size_t>(tri[0])] + w[1] * y[static_cast<std::size_t>(tri[1])] +
         w[2] * y[static_cast<std::size_t>(tri[2])];
}

/// Grid rows from the midline outwards, the two sides alternating (so that the greedy spots of
/// ThinAlternativeLift fall alike on both sides).
std::vector<int> RowsFromMidline(const OcclusalGrid& grid) {
  std::vector<int> rows(static_cast<std::size_t>(grid.ns + 1));
  for (int i = 0; i <= grid.ns; ++i) rows[static_cast<std::size_t>(i)] = i;
  std::stable_sort(rows.begin(), rows.end(),
                   [&](int a, int b) { return std::abs(grid.S(a)) < std::abs(grid.S(b)); });
  return rows;
}

}  // namespace

std::vector<double> AlternativeLift(const OcclusalGrid& grid, const std::vector<double>& lower_y,
                                    const std::vector<Eigen::Vector3i>& triangles) {
  const GridLocator locator(grid, triangles);
  const Eigen::Vector2d shift(0.0, kClass2ShiftMm);
  std::vector<double> lift(grid.num_vertices(), 0.0);
  // Upper vertices: moved by the shift, above the lower triangles there.
  for (int i = 0; i <= grid.ns; ++i) {
    const int hint = ShiftedRowHint(grid, i, kClass2ShiftMm);
    for (int j = 0; j <= grid.nt; ++j) {
      const auto v = static_cast<std::size_t>(grid.Index(i, j));
      const std::optional<GridPoint> at = locator.Locate(grid.xz[v] + shift, hint);
      if (!at) continue;
      const double below = Interpolate(lower_y, triangles[at->triangle], at->weight);
      lift[v] = std::max(0.0, below + kAlternativeMarginMm - lower_y[v]);
    }
  }
  // Lower vertices: below the moved upper triangles over them (the upper at least H_L + lift).
  std::vector<double> upper_y(lower_y.size());
  for (std::size_t v = 0; v < upper_y.size(); ++v) upper_y[v] = lower_y[v] + lift[v];
  for (int i = 0; i <= grid.ns; ++i) {
    const int hint = ShiftedRowHint(grid, i, -kClass2ShiftMm);
    for (int j = 0; j <= grid.nt; ++j) {
      const auto w = static_cast<std::size_t>(grid.Index(i, j));
      const std::optional<GridPoint> at = locator.Locate(grid.xz[w] - shift, hint);
      if (!at) continue;
      const Eigen::Vector3i& tri = triangles[at->triangle];
      const double deficit =
          lower_y[w] + kAlternativeMarginMm - Interpolate(upper_y, tri, at->weight);
      if (deficit <= 0.0) continue;
      for (int k = 0; k < 3; ++k) {
        const auto c = static_cast<std::size_t>(tri[k]);
        lift[c] += deficit;
        upper_y[c] += deficit;
      }
    }
  }
  return lift;
}

std::vector<double> ThinAlternativeLift(const OcclusalGrid& grid, const std::vector<double>& lift,
                                        const std::vector<double>& others) {
  // Greedy spots, each blocking the disc of the spacing around it.
  std::vector<char> blocked(grid.num_vertices(), 0);
  std::vector<int> spots;
  for (const int i : RowsFromMidline(grid)) {
    for (int j = 0; j <= grid.nt; ++j) {
      const int v = grid.Index(i, j);
      const auto k = static_cast<std::size_t>(v);
      if (blocked[k] || lift[k] < others[k] + kSpotBindMm) continue;
      spots.push_back(v);
      ForGridVerticesNear(grid, grid.xz[k], grid.S(i), grid.T(j), kAlternativeSpotSpacingMm,
                          [&](int u, double) { blocked[static_cast<std::size_t>(u)] = 1; });
    }
  }
  const std::vector<double> proximity = ContactProximity(grid, spots);
  std::vector<double> thinned(lift.size());
  for (std::size_t v = 0; v < lift.size(); ++v) {
    thinned[v] = lift[v] + std::min(proximity[v], kSpotLiftRatio * lift[v]);
  }
  return thinned;
}

}  // namespace occlude::io::synthetic
