// Separating-axis triangle/box test: the per-triangle part. For each of the 13
// candidate axes (box faces x, y, z; the triangle normal; each edge crossed with
// x, y, z) the triangle's projected interval is computed once here; the box test
// in the header then projects only the box centre. An axis separates only when
// the intervals are strictly disjoint, so touching sets overlap.
#include "occlude/collision/triangle_box.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace occlude::collision {
namespace {

/// Interval of the three projections.
void Span(double p0, double p1, double p2, double* lo, double* hi) {
  *lo = std::min(p0, std::min(p1, p2));
  *hi = std::max(p0, std::max(p1, p2));
}

}  // namespace

TriangleBoxTester::TriangleBoxTester(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     const Eigen::Vector3d& c)
    : e_{b - a, c - b, a - c}, n_((b - a).cross(c - a)) {
  for (auto& v : lo_) v.setZero();
  for (auto& v : hi_) v.setZero();
  for (int i = 0; i < 3; ++i) Span(a[i], b[i], c[i], &lo_[0][i], &hi_[0][i]);
  Span(n_.dot(a), n_.dot(b), n_.dot(c), &lo_[1][0], &hi_[1][0]);
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d& e = e_[j];
    auto on_x = [&e](const Eigen::Vector3d& p) { return e.y() * p.z() - e.z() * p.y(); };
    auto on_y = [&e](const Eigen::Vector3d& p) { return e.z() * p.x() - e.x() * p.z(); };
    auto on_z = [&e](const Eigen::Vector3d& p) { return e.x() * p.y() - e.y() * p.x(); };
    Span(on_x(a), on_x(b), on_x(c), &lo_[2 + j][0], &hi_[2 + j][0]);
    Span(on_y(a), on_y(b), on_y(c), &lo_[2 + j][1], &hi_[2 + j][1]);
    Span(on_z(a), on_z(b), on_z(c), &lo_[2 + j][2], &hi_[2 + j][2]);
  }
}

}  // namespace occlude::collision
