// TriangleBoxOverlap: analytic cases (touching faces, edges and corners, each
// separating axis family, degenerate triangles) and random triangles against two
// oracles: dense sampling of the triangle, and Sutherland-Hodgman clipping of the
// triangle polygon by the six box planes.
#include "occlude/collision/triangle_box.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace occlude::collision {
namespace {

using V = Eigen::Vector3d;

const V kCenter(0, 0, 0);
const V kHalf(0.5, 0.5, 0.5);

bool Overlap(const V& a, const V& b, const V& c) {
  return TriangleBoxOverlap(kCenter, kHalf, a, b, c);
}

/// Clips the polygon by the half-space {x : sign * (x[axis] - offset) <= 0}.
std::vector<V> ClipHalfSpace(const std::vector<V>& poly, int axis, double sign, double offset) {
  std::vector<V> out;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const V& p = poly[i];
    const V& q = poly[(i + 1) % n];
    const double dp = sign * (p[axis] - offset), dq = sign * (q[axis] - offset);
    if (dp <= 0) out.push_back(p);
    if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) out.push_back(p + (dp / (dp - dq)) * (q - p));
  }
  return out;
}

/// Oracle: the triangle clipped by the box [center - half - grow, center + half + grow]
/// (Sutherland-Hodgman) is non-empty. A point or a segment counts as non-empty.
bool ClipOracle(const V& a, const V& b, const V& c, const V& center, const V& half, double grow) {
  std::vector<V> poly{a, b, c};
  for (int axis = 0; axis < 3 && !poly.empty(); ++axis) {
    poly = ClipHalfSpace(poly, axis, 1.0, center[axis] + half[axis] + grow);
    poly = ClipHalfSpace(poly, axis, -1.0, center[axis] - half[axis] - grow);
  }
  return !poly.empty();
}

bool AnySampleInside(const V& a, const V& b, const V& c, const V& center, const V& half,
                     std::mt19937& rng, int samples) {
  std::uniform_real_distribution<double> w(0, 1);
  for (int s = 0; s < samples; ++s) {
    double x = w(rng), y = w(rng);
    if (x + y > 1) {
      x = 1 - x;
      y = 1 - y;
    }
    const V p = a + x * (b - a) + y * (c - a);
    if (((p - center).cwiseAbs() - half).maxCoeff() <= 0) return true;
  }
  return false;
}

TEST(TriangleBoxTest, InsideOutsideAndCrossing) {
  EXPECT_TRUE(Overlap({-0.1, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}));     // inside
  EXPECT_FALSE(Overlap({2, 2, 2}, {3, 2, 2}, {2, 3, 2}));           // far away
  EXPECT_TRUE(Overlap({-5, -5, 0.2}, {5, -5, 0.2}, {0, 5, 0.2}));   // large, no corner inside
  EXPECT_FALSE(Overlap({0.6, -5, -5}, {0.6, 5, -5}, {0.6, 0, 5}));  // beside a face
}

TEST(TriangleBoxTest, TouchingCountsAsOverlap) {
  // Lying on the face z = 0.5 and just above it.
  EXPECT_TRUE(Overlap({-1, -1, 0.5}, {1, -1, 0.5}, {0, 1, 0.5}));
  EXPECT_FALSE(Overlap({-1, -1, 0.5 + 1e-12}, {1, -1, 0.5 + 1e-12}, {0, 1, 0.5 + 1e-12}));
  // A corner of the triangle on a corner of the box.
  EXPECT_TRUE(Overlap({0.5, 0.5, 0.5}, {1, 0.5, 0.5}, {1, 1, 1}));
  EXPECT_FALSE(Overlap({0.5 + 1e-12, 0.5, 0.5}, {1, 0.5, 0.5}, {1, 1, 1}));
  // Triangle plane x + y = 1 touches the box along its edge x = y = 0.5 (normal axis).
  EXPECT_TRUE(Overlap({1, 0, -1}, {0, 1, -1}, {0.5, 0.5, 2}));
  EXPECT_FALSE(Overlap({1 + 1e-9, 1e-9, -1}, {1e-9, 1 + 1e-9, -1}, {0.5 + 1e-9, 0.5 + 1e-9, 2}));
}

TEST(TriangleBoxTest, EdgeCrossAxisSeparates) {
  // A triangle edge along (1, -1, 1) passing the box edge x = y = 0.5 at distance
  // ~eps; only the axis (1, -1, 1) x z = -(1, 1, 0) separates it.
  const V dir(1, -1, 1), away(1, 1, 0);
  for (const double eps : {-1e-3, 0.0, 1e-9, 1e-3}) {
    const V q(0.5 + eps, 0.5 + eps, 0.0);
    const V a = q - dir, b = q + dir, c = q + 5 * away;
    EXPECT_EQ(Overlap(a, b, c), eps <= 0.0) << eps;
    EXPECT_EQ(Overlap(a, b, 0.5 * (a + b)), eps <= 0.0) << eps;  // as a segment
  }
}

TEST(TriangleBoxTest, DegenerateTriangles) {
  EXPECT_TRUE(Overlap({0.1, 0.1, 0.1}, {0.1, 0.1, 0.1}, {0.1, 0.1, 0.1}));   // point inside
  EXPECT_FALSE(Overlap({0.6, 0.1, 0.1}, {0.6, 0.1, 0.1}, {0.6, 0.1, 0.1}));  // point outside
  EXPECT_TRUE(Overlap({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}));   // point on corner
  EXPECT_TRUE(Overlap({-2, 0, 0}, {2, 0, 0}, {0, 0, 0}));                    // segment through
  EXPECT_FALSE(Overlap({-2, 0.7, 0}, {2, 0.7, 0}, {0, 0.7, 0}));             // segment beside
  EXPECT_FALSE(Overlap({-2, 3.1, 0}, {2, -0.9, 0}, {0.55, 0.55, 0}));  // diagonal, misses corner
  EXPECT_TRUE(Overlap({-2, 2, 0}, {2, -2, 0}, {0, 0, 0}));             // diagonal through
}

TEST(TriangleBoxTest, ZeroSizeBoxIsAPoint) {
  const V zero(0, 0, 0);
  EXPECT_TRUE(TriangleBoxOverlap({0.2, 0.2, 0}, zero, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  EXPECT_TRUE(TriangleBoxOverlap({0.5, 0.5, 0}, zero, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));  // on edge
  EXPECT_FALSE(TriangleBoxOverlap({0.6, 0.6, 0}, zero, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  EXPECT_FALSE(TriangleBoxOverlap({0.2, 0.2, 1e-9}, zero, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
}

TEST(TriangleBoxTest, TesterMatchesFunction) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const TriangleBoxTester tester({0.3, -0.9, 0.2}, {-0.7, 0.8, 0.4}, {0.9, 0.6, -1.1});
  for (int n = 0; n < 2000; ++n) {
    const V center(u(rng), u(rng), u(rng));
    const V half = 0.5 * V(u(rng), u(rng), u(rng)).cwiseAbs();
    EXPECT_EQ(
        tester.Overlaps(center, half),
        TriangleBoxOverlap(center, half, {0.3, -0.9, 0.2}, {-0.7, 0.8, 0.4}, {0.9, 0.6, -1.1}));
  }
}

// Random triangles of several sizes near a unit box: sampled points inside imply
// overlap; the answer agrees with the clipping oracle up to 1e-9 mm.
TEST(TriangleBoxTest, RandomTrianglesAgreeWithOracles) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> pos(-1.2, 1.2);
  std::uniform_real_distribution<double> size(0.01, 2.0);
  std::normal_distribution<double> g(0, 1);
  int overlaps = 0, separated = 0;
  for (int trial = 0; trial < 8000; ++trial) {
    const V base(pos(rng), pos(rng), pos(rng));
    const double sz = size(rng);
    const V a = base, b = base + sz * V(g(rng), g(rng), g(rng)),
            c = base + sz * V(g(rng), g(rng), g(rng));
    const V half = trial % 2 ? kHalf : V(0.5, 0.2, 0.35);
    const bool overlap = TriangleBoxOverlap(kCenter, half, a, b, c);
    if (AnySampleInside(a, b, c, kCenter, half, rng, 100)) {
      ASSERT_TRUE(overlap) << "trial " << trial;
    }
    if (overlap) {
      ++overlaps;
      ASSERT_TRUE(ClipOracle(a, b, c, kCenter, half, 1e-9)) << "trial " << trial;
    } else {
      ++separated;
      ASSERT_FALSE(ClipOracle(a, b, c, kCenter, half, -1e-9)) << "trial " << trial;
    }
  }
  EXPECT_GT(overlaps, 1000);
  EXPECT_GT(separated, 1000);
}

// Degenerate random triangles (segments, points) against the clipping oracle.
TEST(TriangleBoxTest, RandomDegenerateTrianglesAgreeWithOracle) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> pos(-1.5, 1.5), w(0, 1);
  for (int trial = 0; trial < 5000; ++trial) {
    const V a(pos(rng), pos(rng), pos(rng)), b(pos(rng), pos(rng), pos(rng));
    const V c = trial % 3 == 0 ? a : a + w(rng) * (b - a);
    const bool overlap = Overlap(a, b, c);
    if (overlap) {
      ASSERT_TRUE(ClipOracle(a, b, c, kCenter, kHalf, 1e-9)) << trial;
    } else {
      ASSERT_FALSE(ClipOracle(a, b, c, kCenter, kHalf, -1e-9)) << trial;
    }
  }
}

}  // namespace
}  // namespace occlude::collision
