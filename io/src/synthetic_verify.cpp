// Cheap O(n) checks of the synthetic generator's invariants, run on every generated pair: the
// properties the no-penetration and closed-surface arguments rest on (grid does not fold, gap
// non-negative, slabs' backs beyond their occlusal sides, triangle budget met).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

constexpr double kBudgetTolerance = 0.10;  // relative

/// Returns "" when every occlusal triangle of `mesh` (its first `count` triangles) faces up
/// (sign > 0) or down (sign < 0) with a non-zero area: the grid maps (s, t) to xz one to one.
std::string CheckOcclusalFacing(const TriangleMesh& mesh, std::size_t count, double sign,
                                const char* which) {
  for (std::size_t t = 0; t < count; ++t) {
    if (!(sign * mesh.face_normals[t].y() > 0.0)) {
      std::ostringstream err;
      err << which << " occlusal triangle " << t << " does not face " << (sign > 0 ? "+" : "-")
          << "y (the grid folds or a triangle is degenerate)";
      return err.str();
    }
  }
  return "";
}

std::string CheckBacks(const OcclusalFields& fields, const GapResult& gap,
                       const TriangleMesh& lower_L, const TriangleMesh& upper_L,
                       std::size_t grid_vertices) {
  const double lowest = *std::min_element(fields.lower_y.begin(), fields.lower_y.end());
  const double highest = *std::max_element(gap.upper_y.begin(), gap.upper_y.end());
  if (!(lower_L.vertices.back().y() < lowest)) return "lower back not below its occlusal side";
  if (!(upper_L.vertices.back().y() > highest)) return "upper back not above its occlusal side";
  for (std::size_t v = 0; v < grid_vertices; ++v) {
    if (!(gap.upper_y[v] >= fields.lower_y[v])) return "negative gap at a grid vertex";
  }
  for (const int c : gap.contact_vertex) {
    if (gap.upper_y[static_cast<std::size_t>(c)] != fields.lower_y[static_cast<std::size_t>(c)]) {
      return "non-zero gap at a contact vertex";
    }
  }
  return "";
}

std::string CheckBudget(const TriangleMesh& mesh, std::size_t budget) {
  const auto n = static_cast<double>(mesh.num_triangles());
  const auto b = static_cast<double>(budget);
  if (std::abs(n - b) > kBudgetTolerance * b) {
    std::ostringstream err;
    err << mesh.num_triangles() << " triangles for a budget of " << budget;
    return err.str();
  }
  return "";
}

}  // namespace

std::string CheckInvariants(const OcclusalGrid& grid, const OcclusalFields& fields,
                            const GapResult& gap, const TriangleMesh& lower_L,
                            const TriangleMesh& upper_L, std::size_t triangle_budget) {
  const auto occlusal = static_cast<std::size_t>(2 * grid.ns * grid.nt);
  for (const std::string& err :
       {lower_L.ConsistencyError(), upper_L.ConsistencyError(),
        CheckOcclusalFacing(lower_L, occlusal, 1.0, "lower"),
        CheckOcclusalFacing(upper_L, occlusal, -1.0, "upper"),
        CheckBacks(fields, gap, lower_L, upper_L, grid.num_vertices()),
        CheckBudget(lower_L, triangle_budget), CheckBudget(upper_L, triangle_budget)}) {
    if (!err.empty()) return err;
  }
  return "";
}

}  // namespace occlude::io::synthetic
