// The arch's opening (arch_opening.h): monotone-chain hull, then for each hull edge the distance
// from its middle to the nearest crown point (brute force over the points: a few thousand).
#include "arch_opening.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace occlude::analysis {
namespace {

double Cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

double NearestDistance(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& q) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : points) best = std::min(best, (p - q).squaredNorm());
  return std::sqrt(best);
}

}  // namespace

std::vector<Eigen::Vector2d> ConvexHull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower hull
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && Cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

ArchOpening FindArchOpening(const std::vector<Eigen::Vector2d>& crown_points) {
  ArchOpening out;
  const std::vector<Eigen::Vector2d> hull = ConvexHull(crown_points);
  if (hull.size() < 3) return out;
  double best = -1.0, second = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d &a = hull[i], &b = hull[(i + 1) % hull.size()];
    const Eigen::Vector2d middle = 0.5 * (a + b);
    const double depth = NearestDistance(crown_points, middle);
    if (depth > best) {
      second = std::max(best, 0.0);
      best = depth;
      const Eigen::Vector2d edge = (b - a).normalized();
      out.anterior = Eigen::Vector2d(-edge.y(), edge.x());  // inward: the hull is CCW
      out.middle = middle;
      out.width_mm = (b - a).norm();
      out.depth_mm = depth;
    } else {
      second = std::max(second, depth);
    }
  }
  out.confidence = best > 0.0 ? std::clamp(1.0 - second / best, 0.0, 1.0) : 0.0;
  return out;
}

}  // namespace occlude::analysis
