// TrianglesIntersect, TriangleTriangleDistance and TrianglesWithin against
// analytic answers, exactly representable touching configurations (under every
// corner order), symmetry, rigid-motion invariance, an independent edge-crossing
// intersection oracle, a dense-sampling distance oracle and, for coplanar pairs
// (nearly collinear edges included), a separating-axis oracle.
#include "occlude/collision/triangle_triangle.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "test_common.h"

namespace occlude::collision {
namespace {

using Vec = Eigen::Vector3d;
using Tri = std::array<Vec, 3>;

/// Swapping A and B may change rounding only.
constexpr double kSymmetryTol = 1e-12;
/// A rigid motion of both triangles changes the distance by rounding only.
constexpr double kRigidTol = test::kExactMm;
/// A closest point lies on its triangle up to this distance, times the
/// coordinate scale max(1, largest |coordinate|).
constexpr double kOnTriangleTol = 1e-12;
/// A reported common point of intersecting triangles lies on both up to this,
/// times the coordinate scale (it comes from a division by plane values).
constexpr double kCommonPointTol = test::kExactMm;
/// Slack on "distance <= sampled minimum".
constexpr double kSampleSlack = 1e-12;
/// Barycentric subdivisions of the sampling oracle.
constexpr int kSampleGrid = 24;
/// Machine epsilon, and the corner sine under which a triangle is a segment.
constexpr double kEps = std::numeric_limits<double>::epsilon();
const double kSliverSine = std::sqrt(kEps);
/// Exactly representable separation used to pull touching pairs apart.
const double kTinyGap = std::ldexp(1.0, -20);

TriangleDistance Distance(const Tri& a, const Tri& b) {
  return TriangleTriangleDistance(a[0], a[1], a[2], b[0], b[1], b[2]);
}
bool Intersect(const Tri& a, const Tri& b) {
  return TrianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2]);
}
bool Within(const Tri& a, const Tri& b, double max_distance, TriangleDistance* out) {
  return TrianglesWithin(a[0], a[1], a[2], b[0], b[1], b[2], max_distance, out);
}

/// Distance from p to the closed triangle t, computed here independently of the
/// library: the nearest edge point, or the foot on the plane when its
/// (unnormalised) barycentric coordinates are all non-negative.
double DistanceToTriangle(const Vec& p, const Tri& t) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const Vec e = t[(k + 1) % 3] - t[k];
    const double len2 = e.squaredNorm();
    const double s = len2 > 0 ? std::clamp((p - t[k]).dot(e) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (t[k] + s * e)).norm());
  }
  const Vec n = (t[1] - t[0]).cross(t[2] - t[0]);
  if (n.squaredNorm() == 0.0) return best;
  const Vec foot = p - (n.dot(p - t[0]) / n.squaredNorm()) * n;
  for (int k = 0; k < 3; ++k) {
    if (n.dot((t[(k + 1) % 3] - t[k]).cross(foot - t[k])) < 0.0) return best;
  }
  return std::min(best, (p - foot).norm());
}

/// sin of the corner angle of t at t[0].
double CornerSine(const Tri& t) {
  const Vec u = t[1] - t[0];
  const Vec w = t[2] - t[0];
  return u.cross(w).norm() / (u.norm() * w.norm());
}

double MaxEdge(const Tri& t) {
  return std::max({(t[1] - t[0]).norm(), (t[2] - t[1]).norm(), (t[0] - t[2]).norm()});
}

double Scale(const Tri& a, const Tri& b) {
  double m = 1.0;
  for (const Vec& v : a) m = std::max(m, v.cwiseAbs().maxCoeff());
  for (const Vec& v : b) m = std::max(m, v.cwiseAbs().maxCoeff());
  return m;
}

Tri Translated(const Tri& t, const Vec& d) { return {t[0] + d, t[1] + d, t[2] + d}; }

/// The 6 orders of a triangle's corners (both orientations).
std::array<Tri, 6> Orders(const Tri& t) {
  return {{{t[0], t[1], t[2]},
           {t[1], t[2], t[0]},
           {t[2], t[0], t[1]},
           {t[0], t[2], t[1]},
           {t[2], t[1], t[0]},
           {t[1], t[0], t[2]}}};
}

/// Checks the invariants every result must satisfy; `slack` widens the
/// on-triangle tolerances (thin triangles, whose planes are less accurate).
void ExpectConsistent(const Tri& a, const Tri& b, const TriangleDistance& d, double slack = 0.0) {
  const double scale = Scale(a, b);
  if (d.intersecting) {
    EXPECT_EQ(d.distance, 0.0);
    EXPECT_LE(DistanceToTriangle(d.p_a, a), kCommonPointTol * scale + slack);
    EXPECT_LE(DistanceToTriangle(d.p_a, b), kCommonPointTol * scale + slack);
    EXPECT_LE((d.p_a - d.p_b).norm(), kCommonPointTol * scale + slack);
  } else {
    EXPECT_LE(DistanceToTriangle(d.p_a, a), kOnTriangleTol * scale + slack);
    EXPECT_LE(DistanceToTriangle(d.p_b, b), kOnTriangleTol * scale + slack);
    EXPECT_NEAR((d.p_a - d.p_b).norm(), d.distance, kOnTriangleTol * scale);
  }
}

// ----- Analytic cases --------------------------------------------------------

TEST(TriangleTriangleTest, ParallelTrianglesOneApart) {
  const Tri a = {Vec(0, 0, 0), Vec(2, 0, 0), Vec(0, 2, 0)};
  const Tri b = {Vec(0.5, 0.5, 1), Vec(3, 0.5, 1), Vec(0.5, 3, 1)};
  const TriangleDistance d = Distance(a, b);
  EXPECT_FALSE(d.intersecting);
  EXPECT_FALSE(Intersect(a, b));
  EXPECT_NEAR(d.distance, 1.0, 1e-15);
  EXPECT_NEAR(d.p_a.z(), 0.0, 1e-15);
  EXPECT_NEAR(d.p_b.z(), 1.0, 1e-15);
  ExpectConsistent(a, b, d);
}

TEST(TriangleTriangleTest, CrossingTriangles) {
  const Tri a = {Vec(-1, -1, 0), Vec(1, -1, 0), Vec(0, 1, 0)};
  const Tri b = {Vec(0, -0.5, -1), Vec(0, -0.5, 1), Vec(0, 0.5, 0.3)};
  for (const Tri& aa : Orders(a)) {
    for (const Tri& bb : Orders(b)) {
      const TriangleDistance d = Distance(aa, bb);
      EXPECT_TRUE(d.intersecting);
      EXPECT_TRUE(Intersect(aa, bb));
      EXPECT_EQ(d.distance, 0.0);
      ExpectConsistent(aa, bb, d);
    }
  }
}

TEST(TriangleTriangleTest, VertexTouchingFace) {
  const Tri a = {Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0)};
  const Tri b = {Vec(0.25, 0.25, 0), Vec(1, 1, 1), Vec(-1, 0.5, 2)};
  const TriangleDistance d = Distance(a, b);
  EXPECT_TRUE(d.intersecting);
  EXPECT_TRUE(Intersect(a, b));
  EXPECT_EQ(d.distance, 0.0);
  EXPECT_NEAR((d.p_a - Vec(0.25, 0.25, 0)).norm(), 0.0, 1e-15);
  const TriangleDistance lifted = Distance(a, Translated(b, Vec(0, 0, kTinyGap)));
  EXPECT_FALSE(lifted.intersecting);
  EXPECT_NEAR(lifted.distance, kTinyGap, 1e-18);
}

TEST(TriangleTriangleTest, SkewEdgesWithKnownDistance) {
  // A in the plane y = 0 below its top edge on the x axis; B in the plane x = 0
  // above its bottom edge at height 0.75 along y.
  const Tri a = {Vec(-1, 0, 0), Vec(1, 0, 0), Vec(0, 0, -1)};
  const Tri b = {Vec(0, -1, 0.75), Vec(0, 1, 0.75), Vec(0, 0, 1.75)};
  const TriangleDistance d = Distance(a, b);
  EXPECT_FALSE(d.intersecting);
  EXPECT_NEAR(d.distance, 0.75, 1e-15);
  EXPECT_NEAR((d.p_a - Vec(0, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((d.p_b - Vec(0, 0, 0.75)).norm(), 0.0, 1e-15);
  // Skew at an angle: edges (0,0,0)-(1,0,0) and (0.3,-1,2)-(0.3,1,2.5).
  const Tri c = {Vec(0, 0, 0), Vec(1, 0, 0), Vec(0.5, 0, -1)};
  const Tri e = {Vec(0.3, -1, 2), Vec(0.3, 1, 2.5), Vec(0.3, 0, 5)};
  // Line distance: |(d1 x d2) . r| / |d1 x d2| with d1 = x, d2 = (0, 2, 0.5).
  const double expected =
      std::abs(Vec(1, 0, 0).cross(Vec(0, 2, 0.5)).normalized().dot(Vec(0.3, -1, 2)));
  EXPECT_NEAR(Distance(c, e).distance, expected, 1e-15);
}

TEST(TriangleTriangleTest, CoplanarOverlapping) {
  const Tri a = {Vec(0, 0, 0), Vec(2, 0, 0), Vec(0, 2, 0)};
  const Tri b = {Vec(0.5, 0.5, 0), Vec(3, 0.5, 0), Vec(0.5, 3, 0)};
  // Star of David: the edges cross but no corner is inside the other triangle.
  const Tri c = {Vec(0, 0, 1), Vec(4, 0, 1), Vec(2, 3, 1)};
  const Tri e = {Vec(0, 2, 1), Vec(4, 2, 1), Vec(2, -1, 1)};
  // One inside the other.
  const Tri f = {Vec(0.1, 0.1, 0), Vec(0.3, 0.1, 0), Vec(0.1, 0.4, 0)};
  for (const auto& [x, y] : {std::pair{a, b}, std::pair{c, e}, std::pair{a, f}}) {
    const TriangleDistance d = Distance(x, y);
    EXPECT_TRUE(d.intersecting);
    EXPECT_TRUE(Intersect(x, y));
    EXPECT_TRUE(Intersect(y, x));
    ExpectConsistent(x, y, d);
  }
}

TEST(TriangleTriangleTest, CoplanarDisjointWithKnownGap) {
  const Tri a = {Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0)};
  const Tri b = {Vec(1, 1, 0), Vec(2, 1, 0), Vec(1, 2, 0)};
  const TriangleDistance d = Distance(a, b);
  EXPECT_FALSE(d.intersecting);
  EXPECT_FALSE(Intersect(a, b));
  EXPECT_NEAR(d.distance, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR((d.p_a - Vec(0.5, 0.5, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((d.p_b - Vec(1, 1, 0)).norm(), 0.0, 1e-15);
}

TEST(TriangleTriangleTest, IdenticalTriangles) {
  const Tri a = {Vec(0.3, -1.2, 4), Vec(2.2, 0.1, 3.3), Vec(-0.7, 1.9, 5.1)};
  const TriangleDistance d = Distance(a, a);
  EXPECT_TRUE(d.intersecting);
  EXPECT_EQ(d.distance, 0.0);
  ExpectConsistent(a, a, d);
}

TEST(TriangleTriangleTest, DegenerateTriangles) {
  const Tri face = {Vec(-1, -1, 0), Vec(1, -1, 0), Vec(0, 1, 0)};
  // A segment (collinear corners) piercing the face, and one above it.
  const Tri piercing = {Vec(0, 0, -1), Vec(0, 0, 1), Vec(0, 0, 0.25)};
  const Tri above = {Vec(0, 0, 1), Vec(0, 0, 2), Vec(0, 0, 1.5)};
  const Tri point = {Vec(0.2, 0.1, 0.5), Vec(0.2, 0.1, 0.5), Vec(0.2, 0.1, 0.5)};
  const TriangleDistance d = Distance(piercing, face);
  EXPECT_TRUE(d.intersecting);
  EXPECT_NEAR(d.p_a.norm(), 0.0, 1e-15);
  ExpectConsistent(piercing, face, d);
  EXPECT_TRUE(Intersect(face, piercing));
  EXPECT_NEAR(Distance(above, face).distance, 1.0, 1e-15);
  EXPECT_FALSE(Intersect(face, above));
  EXPECT_NEAR(Distance(face, point).distance, 0.5, 1e-15);
  // Two segments crossing at the origin, and two skew segments 1 apart.
  const Tri sx = {Vec(-1, 0, 0), Vec(1, 0, 0), Vec(0, 0, 0)};
  const Tri sy = {Vec(0, -1, 0), Vec(0, 1, 0), Vec(0, 0.5, 0)};
  EXPECT_TRUE(Intersect(sx, sy));
  EXPECT_EQ(Distance(sx, sy).distance, 0.0);
  EXPECT_FALSE(Intersect(sx, Translated(sy, Vec(0, 0, 1))));
  EXPECT_NEAR(Distance(sx, Translated(sy, Vec(0, 0, 1))).distance, 1.0, 1e-15);
  // A sliver (treated as its long edge) crossing a face along that edge.
  const Tri sliver = {Vec(0, 0, 0), Vec(1, 0, 0), Vec(0.5, 1e-12, 0)};
  const Tri wall = {Vec(0.5, -1, -1), Vec(0.5, 1, -1), Vec(0.5, 0, 1)};
  EXPECT_TRUE(Intersect(sliver, wall));
  EXPECT_TRUE(Intersect(wall, sliver));
  EXPECT_FALSE(Intersect(sliver, Translated(wall, Vec(0.6, 0, 0))));
  EXPECT_NEAR(Distance(sliver, Translated(wall, Vec(0.6, 0, 0))).distance, 0.1, 1e-15);
}

TEST(TriangleTriangleTest, NearlyParallelPlanes) {
  const Tri a = {Vec(-10, -10, 0), Vec(10, -10, 0), Vec(0, 10, 0)};
  for (const double tilt : {1e-3, 1e-6, 1e-9}) {
    // B crosses A's plane along y = 0.3 at slope `tilt`.
    const Tri b = {Vec(-1, 0, -0.3 * tilt), Vec(1, 0, -0.3 * tilt), Vec(0, 1, 0.7 * tilt)};
    EXPECT_TRUE(Intersect(a, b)) << tilt;
    ExpectConsistent(a, b, Distance(a, b));
    const double lift = 0.5 * tilt;  // now every corner of B is above A
    const TriangleDistance d = Distance(a, Translated(b, Vec(0, 0, lift)));
    EXPECT_FALSE(d.intersecting) << tilt;
    EXPECT_NEAR(d.distance, lift - 0.3 * tilt, 1e-15) << tilt;
  }
  // Exactly parallel planes 1e-12 apart are apart; 1e-17 apart is rounding.
  const Tri b = {Vec(-1, 0, 1e-12), Vec(1, 0, 1e-12), Vec(0, 1, 1e-12)};
  EXPECT_FALSE(Intersect(a, b));
  EXPECT_NEAR(Distance(a, b).distance, 1e-12, 1e-17);  // lateral rounding
  const Tri c = {Vec(-1, 0, 1e-17), Vec(1, 0, 1e-17), Vec(0, 1, 1e-17)};
  EXPECT_TRUE(Intersect(a, c));
  EXPECT_TRUE(Distance(a, c).intersecting);
}

// ----- Exactly representable touching configurations ------------------------

struct TouchCase {
  std::string name;
  Tri a;
  Tri b;
  Vec away;  ///< moving B along this pulls it off A
};

std::vector<TouchCase> TouchCases() {
  const Tri a = {Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0)};
  return {
      {"vertex on face", a, {Vec(0.25, 0.25, 0), Vec(1, 1, 1), Vec(-1, 0.5, 2)}, Vec(0, 0, 1)},
      {"vertex on edge", a, {Vec(0.5, 0, 0), Vec(1, -1, 1), Vec(0, -1, 2)}, Vec(0, -1, 1)},
      {"vertex on vertex", a, {Vec(1, 0, 0), Vec(2, 1, 1), Vec(2, -1, 1)}, Vec(1, 0, 0)},
      {"edge crosses edge", a, {Vec(0.5, -1, 1), Vec(0.5, 1, -1), Vec(0.5, -1, -1)}, Vec(0, -1, 0)},
      {"edge along face",
       a,
       {Vec(0.25, 0.25, 0), Vec(0.5, 0.25, 0), Vec(0.25, 0.5, 1)},
       Vec(0, 0, 1)},
      {"hinge on shared edge", a, {Vec(0.25, 0, 0), Vec(2, 0, 0), Vec(0.5, 0, 1)}, Vec(0, -1, 1)},
      {"coplanar shared edge", a, {Vec(1, 0, 0), Vec(0, 1, 0), Vec(1, 1, 0)}, Vec(1, 1, 0)},
      {"coplanar shared vertex", a, {Vec(1, 0, 0), Vec(2, 0, 0), Vec(2, 1, 0)}, Vec(1, 0, 0)},
      {"coplanar vertex on edge",
       a,
       {Vec(0.5, 0.5, 0), Vec(1, 1, 0), Vec(0.5, 1.5, 0)},
       Vec(1, 1, 0)},
      {"segment touching face",
       a,
       {Vec(0.25, 0.5, 0), Vec(0.25, 0.5, 2), Vec(0.25, 0.5, 1)},
       Vec(0, 0, 1)},
  };
}

TEST(TriangleTriangleTest, TouchingPairsUnderEveryCornerOrder) {
  for (const Vec& offset : {Vec(0, 0, 0), Vec(96, -48, 80)}) {  // exact shifts
    for (const TouchCase& c : TouchCases()) {
      const Tri a0 = Translated(c.a, offset);
      const Tri b0 = Translated(c.b, offset);
      const Tri b_apart = Translated(b0, kTinyGap * c.away);
      for (const Tri& a : Orders(a0)) {
        for (int k = 0; k < 6; ++k) {
          const Tri b = Orders(b0)[k];
          const Tri bf = Orders(b_apart)[k];
          ASSERT_TRUE(Intersect(a, b)) << c.name;
          ASSERT_TRUE(Intersect(b, a)) << c.name;
          const TriangleDistance d = Distance(a, b);
          ASSERT_TRUE(d.intersecting) << c.name;
          ExpectConsistent(a, b, d);
          ASSERT_FALSE(Intersect(a, bf)) << c.name;
          ASSERT_FALSE(Intersect(bf, a)) << c.name;
          const TriangleDistance f = Distance(a, bf);
          ASSERT_FALSE(f.intersecting) << c.name;
          EXPECT_GT(f.distance, 0.0) << c.name;
          EXPECT_LE(f.distance, kTinyGap * c.away.norm() * (1 + 1e-12)) << c.name;
        }
      }
    }
  }
}

/// A random rotation (uniform enough for tests) and translation.
Eigen::Isometry3d RandomRigid(std::mt19937& rng, double max_shift) {
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(-max_shift, max_shift);
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  q.normalize();
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = q.toRotationMatrix();
  t.translation() = Vec(u(rng), u(rng), u(rng));
  return t;
}

Tri Transformed(const Eigen::Isometry3d& t, const Tri& x) { return {t * x[0], t * x[1], t * x[2]}; }

TEST(TriangleTriangleTest, TouchingPairsStayTouchingUnderRigidMotion) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Isometry3d t = RandomRigid(rng, 100);
    for (const TouchCase& c : TouchCases()) {
      const Tri a = Transformed(t, c.a);
      const Tri b = Transformed(t, c.b);
      const TriangleDistance d = Distance(a, b);
      EXPECT_LE(d.distance, 1e-12) << c.name;  // rounding of the motion only
      ExpectConsistent(a, b, d);
      EXPECT_EQ(Intersect(a, b), d.intersecting) << c.name;
    }
  }
}

TEST(TriangleTriangleTest, CoplanarOverlapStaysIntersectingUnderRigidMotion) {
  // After a motion the corners are no longer exactly coplanar; the rounding
  // bound on the plane values must still send the pair to the 2D test.
  const Tri a = {Vec(0, 0, 0), Vec(2, 0, 0), Vec(0, 2, 0)};
  const Tri b = {Vec(0.5, 0.5, 0), Vec(3, 0.5, 0), Vec(0.5, 3, 0)};
  const Tri c = {Vec(0, 0, 0), Vec(4, 0, 0), Vec(2, 3, 0)};
  const Tri e = {Vec(0, 2, 0), Vec(4, 2, 0), Vec(2, -1, 0)};
  std::mt19937 rng(13);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::Isometry3d t = RandomRigid(rng, 100);
    EXPECT_TRUE(Intersect(Transformed(t, a), Transformed(t, b)));
    EXPECT_TRUE(Intersect(Transformed(t, c), Transformed(t, e)));
    EXPECT_TRUE(Distance(Transformed(t, c), Transformed(t, e)).intersecting);
  }
}

// ----- Random pairs ----------------------------------------------------------

struct RandomPair {
  Tri a;
  Tri b;
  double scale;  ///< size of the triangles
};

/// Random pairs, sizes 0.01..10, most of them near each other or crossing,
/// some far from the origin (mm coordinates of a jaw scan).
std::vector<RandomPair> RandomPairs(unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<RandomPair> pairs;
  for (int i = 0; i < count; ++i) {
    const double scale = std::pow(10.0, -2.0 + 3.0 * unit(rng));
    const double scale_b = scale * std::pow(10.0, unit(rng) - 0.5);
    const Vec origin =
        unit(rng) < 0.3 ? Vec(100 * u(rng), 100 * u(rng), 100 * u(rng)) : Vec::Zero();
    const Vec shift = Vec(u(rng), u(rng), u(rng)).normalized() * (1.2 * scale * unit(rng));
    RandomPair p;
    p.scale = std::max(scale, scale_b);
    for (Vec& v : p.a) v = origin + scale * Vec(u(rng), u(rng), u(rng));
    for (Vec& v : p.b) v = origin + shift + scale_b * Vec(u(rng), u(rng), u(rng));
    pairs.push_back(p);
  }
  return pairs;
}

/// Independent intersection oracle for pairs in general position: some edge of
/// one triangle crosses the other. +1 crossing, 0 apart, -1 too close to call.
int EdgeCrossingOracle(const Tri& a, const Tri& b, double scale) {
  const double tol = 1e-9 * scale;
  bool ambiguous = false;
  auto crosses = [&](const Vec& x, const Vec& y, const Tri& t) {
    const Vec n = (t[1] - t[0]).cross(t[2] - t[0]).normalized();
    const double dx = n.dot(x - t[0]);
    const double dy = n.dot(y - t[0]);
    if (std::abs(dx) < tol || std::abs(dy) < tol) {
      ambiguous = true;
      return false;
    }
    if ((dx > 0) == (dy > 0)) return false;
    const Vec c = x + dx / (dx - dy) * (y - x);
    double min_area = 1e300;  // smallest signed sub-triangle area, in length^2
    for (int k = 0; k < 3; ++k) {
      min_area = std::min(min_area, n.dot((t[(k + 1) % 3] - c).cross(t[(k + 2) % 3] - c)));
    }
    if (std::abs(min_area) < tol * scale) ambiguous = true;
    return min_area > 0;
  };
  for (int i = 0; i < 3; ++i) {
    if (crosses(a[i], a[(i + 1) % 3], b) || crosses(b[i], b[(i + 1) % 3], a)) return 1;
  }
  return ambiguous ? -1 : 0;
}

/// Barycentric grid of a triangle, kSampleGrid subdivisions: every point of
/// the triangle is within MaxEdge / kSampleGrid of a sample.
std::vector<std::array<double, 3>> Samples(const Tri& t) {
  std::vector<std::array<double, 3>> s;
  for (int i = 0; i <= kSampleGrid; ++i) {
    for (int j = 0; i + j <= kSampleGrid; ++j) {
      const Vec p = t[0] + (static_cast<double>(i) / kSampleGrid) * (t[1] - t[0]) +
                    (static_cast<double>(j) / kSampleGrid) * (t[2] - t[0]);
      s.push_back({p.x(), p.y(), p.z()});
    }
  }
  return s;
}

double SampledDistance(const Tri& a, const Tri& b) {
  const auto sa = Samples(a);
  const auto sb = Samples(b);
  double best = 1e300;
  for (const auto& p : sa) {
    for (const auto& q : sb) {
      const double dx = p[0] - q[0];
      const double dy = p[1] - q[1];
      const double dz = p[2] - q[2];
      best = std::min(best, dx * dx + dy * dy + dz * dz);
    }
  }
  return std::sqrt(best);
}

TEST(TriangleTriangleTest, RandomPairsAgainstSamplingOracle) {
  int crossing = 0;
  for (const RandomPair& p : RandomPairs(2024, 400)) {
    const TriangleDistance d = Distance(p.a, p.b);
    ExpectConsistent(p.a, p.b, d);
    const double sampled = SampledDistance(p.a, p.b);
    const double density = (MaxEdge(p.a) + MaxEdge(p.b)) / kSampleGrid;
    ASSERT_LE(d.distance, sampled + kSampleSlack);
    ASSERT_GE(d.distance, sampled - density - kSampleSlack);
    crossing += d.intersecting ? 1 : 0;
  }
  EXPECT_GT(crossing, 40);  // the generator does exercise both outcomes
  EXPECT_LT(crossing, 360);
}

TEST(TriangleTriangleTest, SliversAgainstSamplingOracle) {
  // Thin triangles of every flatness: segments (sin <= 1.5e-8), flat ones
  // (planes accurate to eps / sin only) and ordinary ones.
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> unit(0, 1);
  int crossing = 0;
  for (RandomPair p : RandomPairs(31, 300)) {
    const Vec along = p.a[1] - p.a[0];
    const Vec side = along.cross(Vec(u(rng), u(rng), u(rng))).normalized();
    const double thinness = std::pow(10.0, -12.0 + 11.0 * unit(rng));
    p.a[2] = p.a[0] + unit(rng) * along + thinness * along.norm() * side;
    // A normal of relative accuracy eps / sin places points to that, times size.
    const double sine = CornerSine(p.a);
    const double slack = sine > kSliverSine ? 8 * kEps / sine * MaxEdge(p.a) : 0.0;
    const TriangleDistance d = Distance(p.a, p.b);
    ExpectConsistent(p.a, p.b, d, slack);
    EXPECT_NEAR(d.distance, Distance(p.b, p.a).distance, kSymmetryTol);
    const double sampled = SampledDistance(p.a, p.b);
    const double density = (MaxEdge(p.a) + MaxEdge(p.b)) / kSampleGrid;
    ASSERT_LE(d.distance, sampled + kSampleSlack);
    ASSERT_GE(d.distance, sampled - density - kSampleSlack);
    crossing += d.intersecting ? 1 : 0;
  }
  EXPECT_GT(crossing, 10);
}

TEST(TriangleTriangleTest, RandomPairsIntersectionMatchesOracleAndDistance) {
  int called = 0;
  for (const RandomPair& p : RandomPairs(99, 20000)) {
    const bool hit = Intersect(p.a, p.b);
    const TriangleDistance d = Distance(p.a, p.b);
    ASSERT_EQ(hit, d.intersecting);
    ASSERT_EQ(hit, d.distance == 0.0);
    ASSERT_EQ(hit, Intersect(p.b, p.a));
    const int oracle = EdgeCrossingOracle(p.a, p.b, p.scale);
    if (oracle < 0) continue;
    ++called;
    ASSERT_EQ(hit, oracle == 1);
  }
  EXPECT_GT(called, 19000);
}

TEST(TriangleTriangleTest, SymmetricInAAndB) {
  for (const RandomPair& p : RandomPairs(5, 3000)) {
    const TriangleDistance ab = Distance(p.a, p.b);
    const TriangleDistance ba = Distance(p.b, p.a);
    ASSERT_NEAR(ab.distance, ba.distance, kSymmetryTol);
    ASSERT_EQ(ab.intersecting, ba.intersecting);
  }
}

TEST(TriangleTriangleTest, InvariantUnderRigidMotion) {
  std::mt19937 rng(11);
  for (const RandomPair& p : RandomPairs(6, 3000)) {
    const Eigen::Isometry3d t = RandomRigid(rng, 50);
    const TriangleDistance d = Distance(p.a, p.b);
    const TriangleDistance m = Distance(Transformed(t, p.a), Transformed(t, p.b));
    ASSERT_NEAR(d.distance, m.distance, kRigidTol);
  }
}

TEST(TriangleTriangleTest, WithinAgreesWithDistance) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0, 1);
  int yes = 0;
  int no = 0;
  for (const RandomPair& p : RandomPairs(8, 5000)) {
    const TriangleDistance d = Distance(p.a, p.b);
    const double r = d.distance;
    for (const double md : {0.0, 0.5 * r, r * (1 - 1e-6), r * (1 + 1e-6), 2 * r + 1e-3 * p.scale,
                            2 * p.scale * unit(rng), 1e-3 * p.scale * unit(rng)}) {
      if (md != r && std::abs(md - r) <= 1e-12 * Scale(p.a, p.b)) continue;  // too close
      TriangleDistance w;
      const bool within = Within(p.a, p.b, md, &w);
      ASSERT_EQ(within, r <= md) << "distance " << r << " max " << md;
      ASSERT_EQ(within, Within(p.a, p.b, md, nullptr));
      if (within) {
        ++yes;
        ASSERT_EQ(w.distance, d.distance);
        ASSERT_EQ(w.intersecting, d.intersecting);
        ASSERT_EQ(w.p_a, d.p_a);
        ASSERT_EQ(w.p_b, d.p_b);
      } else {
        ++no;
        ASSERT_GT(w.distance, md);
        ASSERT_LE(w.distance, r + 1e-12 * Scale(p.a, p.b));  // a lower bound, up to rounding
        ASSERT_FALSE(w.intersecting);
      }
    }
  }
  EXPECT_GT(yes, 1000);
  EXPECT_GT(no, 1000);
  TriangleDistance w;
  const Tri a = {Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0)};
  EXPECT_FALSE(Within(a, a, -1.0, &w));
  EXPECT_GT(w.distance, -1.0);
}

// ----- Coplanar pairs with nearly collinear edges ----------------------------

/// Distance of two coplanar triangles known to be disjoint, independently of
/// the library: the closest pair of disjoint coplanar triangles has a corner of
/// one of them.
double CoplanarDisjointDistance(const Tri& a, const Tri& b) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    best = std::min({best, DistanceToTriangle(a[k], b), DistanceToTriangle(b[k], a)});
  }
  return best;
}

using Tri2 = std::array<Eigen::Vector2d, 3>;

/// Independent 2D oracle: the largest gap between the projections of the two
/// triangles on the 6 edge normals (separating axis theorem). Positive: the
/// triangles are apart, by at least that much; zero or negative: they meet
/// (touching counts). The triangles must have non-zero area.
double SeparatingAxisGap(const Tri2& a, const Tri2& b) {
  double gap = -std::numeric_limits<double>::infinity();
  for (const Tri2* t : {&a, &b}) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d e = (*t)[(k + 1) % 3] - (*t)[k];
      const Eigen::Vector2d n = Eigen::Vector2d(-e.y(), e.x()).normalized();
      double lo_a = std::numeric_limits<double>::infinity();
      double hi_a = -lo_a;
      double lo_b = lo_a;
      double hi_b = -lo_a;
      for (int i = 0; i < 3; ++i) {
        lo_a = std::min(lo_a, n.dot(a[i]));
        hi_a = std::max(hi_a, n.dot(a[i]));
        lo_b = std::min(lo_b, n.dot(b[i]));
        hi_b = std::max(hi_b, n.dot(b[i]));
      }
      gap = std::max({gap, lo_b - hi_a, lo_a - hi_b});
    }
  }
  return gap;
}

/// The 2D triangle t placed in the coordinate plane normal to `axis` at height
/// `level` (in-plane coordinates on the two other axes, in cyclic order).
Tri InAxisPlane(const Tri2& t, int axis, double level) {
  Tri r;
  for (int i = 0; i < 3; ++i) {
    r[i][axis] = level;
    r[i][(axis + 1) % 3] = t[i].x();
    r[i][(axis + 2) % 3] = t[i].y();
  }
  return r;
}

TEST(TriangleTriangleTest, CoplanarNearlyCollinearEdgesTwelveApart) {
  // Reported: two triangles in the plane y = -6, 12 mm apart, with an edge of
  // each on nearly the same line. The 2D orientations of those edges round to
  // zero, which must not be read as contact without the ends being within the
  // other edge's extent.
  const Tri a = {Vec(-17.493884909091364, -6, -14.538682564429198),
                 Vec(-18.218409445386321, -6, -13.355538712548226),
                 Vec(-17.304049085772526, -6, -13.529140917741405)};
  const Tri b = {Vec(-30.105094120365663, -6, -11.098710045036901),
                 Vec(-31.019454479979458, -6, -10.925107839843722),
                 Vec(-30.816331485049211, -6, -9.8661040604646129)};
  const double expected = CoplanarDisjointDistance(a, b);
  ASSERT_GT(expected, 12.0);
  ASSERT_LT(expected, 13.0);
  auto check = [&](const Tri& x, const Tri& y) {
    for (const Tri& xx : Orders(x)) {
      for (const Tri& yy : Orders(y)) {
        ASSERT_FALSE(Intersect(xx, yy));
        ASSERT_FALSE(Intersect(yy, xx));
        const TriangleDistance d = Distance(xx, yy);
        ASSERT_FALSE(d.intersecting);
        ASSERT_NEAR(d.distance, expected, 1e-9);
        ExpectConsistent(xx, yy, d);
        TriangleDistance w;
        ASSERT_TRUE(Within(xx, yy, 1.001 * expected, &w));
        ASSERT_FALSE(w.intersecting);
        ASSERT_EQ(w.distance, d.distance);
        ASSERT_FALSE(Within(xx, yy, 0.999 * expected, nullptr));
        ASSERT_FALSE(Within(xx, yy, 1.0, nullptr));
      }
    }
  };
  check(a, b);
  std::mt19937 rng(12);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Isometry3d t = RandomRigid(rng, 50);
    check(Transformed(t, a), Transformed(t, b));
  }
}

TEST(TriangleTriangleTest, RandomCoplanarPairsAgainstSeparatingAxisOracle) {
  // Pairs in a coordinate plane at jaw-scan coordinates (tens of mm), about
  // half of them with an edge of B on the line through an edge of A (collinear
  // up to the rounding of the coordinates), anywhere from overlapping to 20 mm
  // apart along it; then the same pairs after a rigid motion (no longer exactly
  // coplanar). Compared with the separating-axis oracle, skipping pairs within
  // kUndecided of touching, where rounding may decide either way.
  constexpr double kUndecided = 1e-9;
  std::mt19937 rng(2718);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> unit(0, 1);
  const double levels[] = {-6.0, 0.0, 14.75, -31.3};
  int decided = 0;
  int apart = 0;
  int apart_collinear = 0;
  int meeting = 0;
  for (int trial = 0; trial < 10000; ++trial) {
    const double size = 0.5 + 1.5 * unit(rng);
    const Eigen::Vector2d center(-20 + 15 * u(rng), -20 + 15 * u(rng));
    Tri2 a2;
    for (auto& v : a2) v = center + size * Eigen::Vector2d(u(rng), u(rng));
    auto well_shaped = [](const Tri2& t) {
      const Eigen::Vector2d e1 = t[1] - t[0];
      const Eigen::Vector2d e2 = t[2] - t[0];
      return std::abs(e1.x() * e2.y() - e1.y() * e2.x()) > 0.05 * e1.norm() * e2.norm();
    };
    if (!well_shaped(a2)) continue;
    Tri2 b2;
    const bool collinear = trial % 2 == 0;
    if (collinear) {
      // B's edge (b0, b1) on the line p + s (q - p) through A's edge k.
      const int k = trial / 2 % 3;
      const Eigen::Vector2d p = a2[k];
      const Eigen::Vector2d e = a2[(k + 1) % 3] - p;
      const double s0 = 8 * u(rng);
      const double s1 = s0 + (0.2 + 2 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
      b2[0] = p + s0 * e;
      b2[1] = p + s1 * e;
      const double side = (0.2 + 1.3 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
      b2[2] = p + (0.5 * (s0 + s1) + 0.5 * u(rng)) * e + side * Eigen::Vector2d(-e.y(), e.x());
      std::shuffle(b2.begin(), b2.end(), rng);
    } else {
      const Eigen::Vector2d shift = 2.5 * size * Eigen::Vector2d(u(rng), u(rng));
      for (auto& v : b2) v = center + shift + size * Eigen::Vector2d(u(rng), u(rng));
    }
    if (!well_shaped(b2)) continue;
    const double gap = SeparatingAxisGap(a2, b2);
    if (std::abs(gap) < kUndecided) continue;
    ++decided;
    const bool expected = gap < 0.0;
    apart += expected ? 0 : 1;
    apart_collinear += !expected && collinear ? 1 : 0;
    meeting += expected ? 1 : 0;
    const int axis = trial % 3;
    const double level = levels[trial / 3 % 4];
    const Tri a = InAxisPlane(a2, axis, level);
    const Tri b = InAxisPlane(b2, axis, level);
    const Eigen::Isometry3d t = RandomRigid(rng, 50);
    for (const auto& [x, y] : {std::pair{a, b}, std::pair{Transformed(t, a), Transformed(t, b)}}) {
      ASSERT_EQ(Intersect(x, y), expected) << "trial " << trial << " gap " << gap;
      ASSERT_EQ(Intersect(y, x), expected) << "trial " << trial << " gap " << gap;
      const TriangleDistance d = Distance(x, y);
      ASSERT_EQ(d.intersecting, expected) << "trial " << trial;
      ExpectConsistent(x, y, d);
      if (expected) {
        ASSERT_EQ(d.distance, 0.0);
        continue;
      }
      const double reference = CoplanarDisjointDistance(x, y);
      ASSERT_GE(reference, gap - kUndecided);  // the axis gap is a lower bound
      ASSERT_NEAR(d.distance, reference, kUndecided) << "trial " << trial;
      ASSERT_TRUE(Within(x, y, reference + kUndecided, nullptr)) << "trial " << trial;
      ASSERT_FALSE(Within(x, y, reference - kUndecided, nullptr)) << "trial " << trial;
    }
  }
  EXPECT_GT(decided, 8000);  // the generator exercises both outcomes, and
  EXPECT_GT(meeting, 600);   // collinear edges far apart in particular
  EXPECT_GT(apart, 6000);
  EXPECT_GT(apart_collinear, 3000);
}

TEST(TriangleTriangleTest, CoplanarPairsSharingACornerTouch) {
  // A corner of B placed exactly on a corner of A: the pair touches whatever
  // the rest of B does, in a coordinate plane and after a rigid motion.
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 1000; ++trial) {
    const Eigen::Vector2d center(-20 + 15 * u(rng), -20 + 15 * u(rng));
    Tri2 a2;
    Tri2 b2;
    for (auto& v : a2) v = center + 2 * Eigen::Vector2d(u(rng), u(rng));
    for (auto& v : b2) v = center + 4 * Eigen::Vector2d(u(rng), u(rng));
    b2[trial % 3] = a2[trial / 3 % 3];
    const Tri a = InAxisPlane(a2, trial % 3, -6.0);
    const Tri b = InAxisPlane(b2, trial % 3, -6.0);
    const Eigen::Isometry3d t = RandomRigid(rng, 50);
    for (const auto& [x, y] : {std::pair{a, b}, std::pair{Transformed(t, a), Transformed(t, b)}}) {
      ASSERT_TRUE(Intersect(x, y)) << "trial " << trial;
      ASSERT_TRUE(Intersect(y, x)) << "trial " << trial;
      ASSERT_TRUE(Distance(x, y).intersecting) << "trial " << trial;
    }
  }
}

}  // namespace
}  // namespace occlude::collision
