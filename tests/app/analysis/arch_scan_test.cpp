// The arch analysis's two scans of every vertex and triangle against brute force: the height
// map (RasterizeTop) equals scanning every cell of each triangle's box with the same exact test,
// and ArchCurve::Project equals the nearest of every segment of its window (the lowest among
// equals), on random triangles and points with fixed seeds, past the curve's ends too.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "analysis/arch_curve.h"
#include "analysis/height_map.h"

namespace occlude::analysis {
namespace {

// The height map by scanning every cell of the grid for every triangle (the definition).
std::vector<double> BruteHeights(const io::TriangleMesh& mesh, const HeightMap& like) {
  std::vector<double> h(like.height.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    Eigen::Vector3d p[3];
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = mesh.corner(t, c);
      p[c] << like.axes.Plane(v), like.axes.Height(v);
    }
    const Eigen::Vector2d a = p[0].head<2>(), b = p[1].head<2>(), c = p[2].head<2>();
    const double det = (b - a).x() * (c - a).y() - (c - a).x() * (b - a).y();
    if (std::abs(det) < 1e-14) continue;
    for (int k = 0; k < like.nx * like.ny; ++k) {
      const Eigen::Vector2d q = like.Centre(k);
      const double l1 = ((b - q).x() * (c - q).y() - (c - q).x() * (b - q).y()) / det;
      const double l2 = ((c - q).x() * (a - q).y() - (a - q).x() * (c - q).y()) / det;
      const double l3 = 1.0 - l1 - l2;
      if (l1 < 0.0 || l2 < 0.0 || l3 < 0.0) continue;
      const double z = l1 * p[0].z() + l2 * p[1].z() + l3 * p[2].z();
      auto& cell = h[static_cast<std::size_t>(k)];
      if (std::isnan(cell) || z > cell) cell = z;
    }
  }
  return h;
}

TEST(ArchScanTest, HeightMapEqualsScanningEveryCell) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> xy(-6.0, 6.0), z(-2.0, 2.0), small(-0.4, 0.4);
  io::TriangleMesh mesh;
  for (int t = 0; t < 400; ++t) {
    // Large, small and sliver triangles.
    const Eigen::Vector3d a(xy(rng), xy(rng), z(rng));
    const double scale = t % 3 == 0 ? 1.0 : 0.2;
    const Eigen::Vector3d b = a + Eigen::Vector3d(xy(rng), xy(rng), z(rng)) * scale;
    const Eigen::Vector3d c =
        t % 7 == 0 ? Eigen::Vector3d(a + 0.5 * (b - a) +
                                     Eigen::Vector3d(small(rng) * 1e-3, small(rng) * 1e-3, 0))
                   : Eigen::Vector3d(a + Eigen::Vector3d(xy(rng), xy(rng), z(rng)) * scale);
    const int base = static_cast<int>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), {a, b, c});
    mesh.triangles.emplace_back(base, base + 1, base + 2);
  }
  ViewAxes axes;
  axes.e1_J = Eigen::Vector3d(1, 0.2, 0.1).normalized();
  axes.up_J = Eigen::Vector3d(-0.1, 0.3, 1).normalized();
  axes.e1_J = (axes.e1_J - axes.e1_J.dot(axes.up_J) * axes.up_J).normalized();
  axes.e2_J = axes.up_J.cross(axes.e1_J);
  const HeightMap map = RasterizeTop(mesh, {}, axes, 0.13);
  const std::vector<double> brute = BruteHeights(mesh, map);
  ASSERT_EQ(map.height.size(), brute.size());
  int filled = 0;
  for (std::size_t k = 0; k < brute.size(); ++k) {
    if (std::isnan(brute[k])) {
      EXPECT_TRUE(std::isnan(map.height[k])) << k;
      continue;
    }
    EXPECT_EQ(map.height[k], brute[k]) << k;
    ++filled;
  }
  EXPECT_GT(filled, 1000);
}

// A U of stations every `step` mm: a parabola's arc, right to left, with its polar angles.
ArchCurve UCurve(double step) {
  ArchCurve curve;
  curve.step = step;
  std::vector<Eigen::Vector2d> dense;
  for (double x = -25.0; x <= 25.0; x += 0.001) dense.emplace_back(x, 30.0 - 0.045 * x * x);
  curve.q.push_back(dense.front());
  double since = 0.0;
  for (std::size_t i = 1; i < dense.size(); ++i) {
    since += (dense[i] - dense[i - 1]).norm();
    if (since >= step) {
      curve.q.push_back(dense[i]);
      since = 0.0;
    }
  }
  curve.top.assign(curve.q.size(), 0.0);
  curve.centre = Eigen::Vector2d(0.0, 10.0);
  for (const auto& p : curve.q) curve.angle.push_back(ArchAngle(curve.centre, p));
  return curve;
}

// Stations every `step` mm out along +x from (0, 0) to (3, 0), round a half circle of radius
// 1.5 mm and back along -x at y = 3 to (-4, 3): the first segment's line, which extends past
// the curve's end, passes under the returning branch. Its polar angles are made up (decreasing)
// and its centre placed so that `p` starts its search at station `k0` (ArchAngle(centre, p) =
// angle[k0]), within the 12 mm window of the first segment.
ArchCurve HookedCurve(double step, const Eigen::Vector2d& p, std::size_t k0) {
  ArchCurve curve;
  curve.step = step;
  constexpr double kPi = 3.14159265358979323846, kRadius = 1.5;
  for (double x = 0.0; x < 3.0; x += step) curve.q.emplace_back(x, 0.0);
  for (double a = 0.0; a < kPi; a += step / kRadius)
    curve.q.emplace_back(3.0 + kRadius * std::sin(a), kRadius - kRadius * std::cos(a));
  for (double x = 3.0; x >= -4.0; x -= step) curve.q.emplace_back(x, 3.0);
  curve.top.assign(curve.q.size(), 0.0);
  for (std::size_t k = 0; k < curve.q.size(); ++k)
    curve.angle.push_back(3.0 - 6.0 * static_cast<double>(k) / static_cast<double>(curve.q.size()));
  const double a = curve.angle[k0];
  curve.centre = p - Eigen::Vector2d(-std::sin(a), std::cos(a));
  return curve;
}

// The projection by trying every segment of the window in order (the definition).
ArchCurve::Projection BruteProject(const ArchCurve& c, const Eigen::Vector2d& p) {
  const double a = ArchAngle(c.centre, p);
  const auto k0 = static_cast<long>(
      std::lower_bound(c.angle.begin(), c.angle.end(), a, std::greater<double>()) -
      c.angle.begin());
  const long n = static_cast<long>(c.q.size());
  const long window = static_cast<long>(std::ceil(12.0 / c.step));
  double best = std::numeric_limits<double>::infinity();
  ArchCurve::Projection out;
  for (long k = std::max(0L, k0 - window); k < std::min(n - 1, k0 + window); ++k) {
    const Eigen::Vector2d qk = c.q[static_cast<std::size_t>(k)];
    const Eigen::Vector2d d = c.q[static_cast<std::size_t>(k + 1)] - qk;
    double f = (p - qk).dot(d) / d.squaredNorm();
    if (k > 0) f = std::max(f, 0.0);
    if (k < n - 2) f = std::min(f, 1.0);
    const double dist = (p - (qk + f * d)).squaredNorm();
    if (dist < best) {
      best = dist;
      out.s = (static_cast<double>(k) + f) * c.step;
      out.t = (p - (qk + f * d)).dot(Eigen::Vector2d(-d.y(), d.x()).normalized());
    }
  }
  return out;
}

TEST(ArchScanTest, ProjectEqualsTheNearestOfEverySegmentOfItsWindow) {
  const ArchCurve curve = UCurve(0.25);
  ASSERT_GT(curve.q.size(), 100u);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> x(-40.0, 40.0), y(-25.0, 45.0);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    // Anywhere, and near the curve (on stations, between them, past its ends).
    Eigen::Vector2d p(x(rng), y(rng));
    if (i % 2 == 1) {
      const auto k = static_cast<std::size_t>(rng() % curve.q.size());
      p = curve.q[k] + 0.01 * Eigen::Vector2d(x(rng), y(rng)) * ((i % 4 == 1) ? 1.0 : 0.0);
    }
    const ArchCurve::Projection fast = curve.Project(p), brute = BruteProject(curve, p);
    ASSERT_EQ(fast.s, brute.s) << p.transpose();
    ASSERT_EQ(fast.t, brute.t) << p.transpose();
    ++checked;
  }
  // Past the ends, along and beside the end segments' lines (which extend past the ends).
  const std::size_t last = curve.q.size() - 1;
  for (const auto& [end, inner] :
       {std::pair{std::size_t{0}, std::size_t{1}}, std::pair{last, last - 1}}) {
    const Eigen::Vector2d out = (curve.q[end] - curve.q[inner]).normalized();
    const Eigen::Vector2d side(-out.y(), out.x());
    for (double along = 0.05; along < 15.0; along += 0.37) {
      for (double beside = -6.0; beside <= 6.0; beside += 0.5) {
        const Eigen::Vector2d p = curve.q[end] + along * out + beside * side;
        const ArchCurve::Projection fast = curve.Project(p), brute = BruteProject(curve, p);
        ASSERT_EQ(fast.s, brute.s) << p.transpose();
        ASSERT_EQ(fast.t, brute.t) << p.transpose();
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 20000);
  // Points on the first segment's line past the end, nearer to it than to the branch above,
  // whose search starts on the half circle: the branch is met first.
  for (double past = -3.5; past <= -0.5; past += 0.5) {
    const Eigen::Vector2d p(past, 0.4);
    const ArchCurve hooked = HookedCurve(0.25, p, 20);
    const ArchCurve::Projection fast = hooked.Project(p), brute = BruteProject(hooked, p);
    EXPECT_LT(brute.s, 0.0) << past;  // on the line past the end
    EXPECT_NEAR(brute.t, 0.4, 1e-9) << past;
    ASSERT_EQ(fast.s, brute.s) << past;
    ASSERT_EQ(fast.t, brute.t) << past;
  }
}

}  // namespace
}  // namespace occlude::analysis
