// Sphere-tree queries against brute-force oracles on small meshes: no missed
// contact, all sphere modes identical, boolean = all-pairs, exact refinement =
// brute-force minimum distance, invariance and symmetry, work budget.
#include "occlude/collision/collide.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <set>

#include "occlude/collision/morton.h"
#include "occlude/collision/sphere_table.h"
#include "occlude/collision/triangle_triangle.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

using io::TriangleMesh;

SphereTree Tree(const TriangleMesh& m, double s,
                SphereMode explicit_from = SphereMode::kOptimized) {
  SphereTreeOptions o;
  o.voxelize.voxel_size_mm = s;
  o.explicit_from = explicit_from;
  return SphereTree::Build(std::make_shared<TriangleMesh>(m), o);
}

Eigen::Isometry3d RandomPose(std::mt19937& rng, double max_translation, double max_angle_rad) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  X.linear() = Eigen::AngleAxisd(max_angle_rad * u(rng), axis).toRotationMatrix();
  X.translation() = max_translation * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return X;
}

std::vector<VoxelPair> Sorted(std::vector<VoxelPair> p) {
  std::sort(p.begin(), p.end());
  return p;
}

// All voxel pairs passing the leaf test, by brute force over every pair.
std::vector<VoxelPair> BruteForcePairs(const SphereTree& a, const SphereTree& b,
                                       const Eigen::Isometry3d& X_AB, double delta) {
  std::vector<VoxelPair> out;
  const auto& oa = a.octree();
  const auto& ob = b.octree();
  // Grown cubes farther apart than the sum of their circumradii cannot overlap:
  // a cheap, conservative prefilter before the exact test.
  const double reach =
      kCubeCircumradius * (a.voxel_size_mm() + b.voxel_size_mm() + 2.0 * delta) + 1e-9;
  std::vector<Eigen::Vector3d> centers_b;
  for (std::uint32_t j = 0; j < ob.num_leaves(); ++j)
    centers_b.push_back(X_AB * b.CubeCenter(ob.leaf_begin() + j, 0));
  for (std::uint32_t i = 0; i < oa.num_leaves(); ++i) {
    const Eigen::Vector3d ca = a.CubeCenter(oa.leaf_begin() + i, 0);
    for (std::uint32_t j = 0; j < ob.num_leaves(); ++j) {
      const Eigen::Vector3d& cb = centers_b[j];
      if ((cb - ca).squaredNorm() > reach * reach) continue;
      if (GrownCubesOverlap(ca, 0.5 * a.voxel_size_mm(), cb, 0.5 * b.voxel_size_mm(), X_AB.linear(),
                            0.5 * delta)) {
        out.push_back({i, j});
      }
    }
  }
  return out;
}

struct BruteTriangles {
  double min_distance = std::numeric_limits<double>::infinity();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> within;  // pairs within delta
};

BruteTriangles BruteForceTriangles(const TriangleMesh& ma, const TriangleMesh& mb,
                                   const Eigen::Isometry3d& X_AB, double delta) {
  BruteTriangles r;
  for (std::uint32_t i = 0; i < ma.num_triangles(); ++i) {
    for (std::uint32_t j = 0; j < mb.num_triangles(); ++j) {
      const TriangleDistance d = TriangleTriangleDistance(
          ma.corner(i, 0), ma.corner(i, 1), ma.corner(i, 2), X_AB * mb.corner(j, 0),
          X_AB * mb.corner(j, 1), X_AB * mb.corner(j, 2));
      r.min_distance = std::min(r.min_distance, d.distance);
      if (d.distance <= delta) r.within.emplace_back(i, j);
    }
  }
  return r;
}

bool PairCovers(const SphereTree& a, const SphereTree& b, const VoxelPair& p, std::uint32_t ta,
                std::uint32_t tb) {
  const auto& ga = a.grid();
  const auto& gb = b.grid();
  const bool has_a = std::find(ga.triangle_indices.begin() + ga.triangles_begin(p.voxel_a),
                               ga.triangle_indices.begin() + ga.triangles_end(p.voxel_a),
                               ta) != ga.triangle_indices.begin() + ga.triangles_end(p.voxel_a);
  const bool has_b = std::find(gb.triangle_indices.begin() + gb.triangles_begin(p.voxel_b),
                               gb.triangle_indices.begin() + gb.triangles_end(p.voxel_b),
                               tb) != gb.triangle_indices.begin() + gb.triangles_end(p.voxel_b);
  return has_a && has_b;
}

class CollideOracleTest : public ::testing::Test {
 protected:
  TriangleMesh sphere_ = test::MakeSphere({0, 0, 0}, 1.0, 8, 12);
  TriangleMesh box_ = test::MakeBox({-0.6, -0.4, -0.5}, {0.7, 0.5, 0.3});
};

TEST_F(CollideOracleTest, AllModesMatchBruteForceLeafPairsAndMissNoContact) {
  std::mt19937 rng(2024);
  const double s = 0.15;
  const SphereTree a = Tree(sphere_, s);
  const SphereTree b = Tree(box_, 0.2, SphereMode::kSimple);
  int poses_with_contacts = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double delta = (trial % 3) * 0.05;
    Eigen::Isometry3d X_AB = RandomPose(rng, 1.0, 3.0);
    X_AB.translation() += Eigen::Vector3d(1.3, 0, 0);
    const auto expected = Sorted(BruteForcePairs(a, b, X_AB, delta));
    CollisionRequest req;
    req.delta_mm = delta;
    CollisionResult res;
    for (SphereMode mode : {SphereMode::kSimple, SphereMode::kOptimized, SphereMode::kExplicit}) {
      req.spheres = mode;
      Collide(a, b, X_AB, req, &res);
      ASSERT_EQ(Sorted(res.pairs), expected) << "trial " << trial << " mode " << ToString(mode);
      ASSERT_TRUE(res.complete);
      ASSERT_EQ(res.overlap, !expected.empty());
    }
    // No missed contact: every triangle pair within delta lies in a reported voxel pair.
    const BruteTriangles brute = BruteForceTriangles(a.mesh(), b.mesh(), X_AB, delta);
    poses_with_contacts += brute.within.empty() ? 0 : 1;
    for (const auto& [ta, tb] : brute.within) {
      const bool covered = std::any_of(res.pairs.begin(), res.pairs.end(), [&](const VoxelPair& p) {
        return PairCovers(a, b, p, ta, tb);
      });
      ASSERT_TRUE(covered) << "missed triangles " << ta << "," << tb << " at trial " << trial;
    }
  }
  EXPECT_GT(poses_with_contacts, 10);  // the poses do exercise contact
}

TEST_F(CollideOracleTest, BooleanAgreesWithAllPairs) {
  std::mt19937 rng(5);
  const SphereTree a = Tree(sphere_, 0.1);
  const SphereTree b = Tree(box_, 0.1);
  int hits = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Eigen::Isometry3d X_AB = RandomPose(rng, 0.6, 3.0);
    X_AB.translation() += Eigen::Vector3d(1.45, 0, 0);
    CollisionRequest req;
    req.delta_mm = 0.02;
    CollisionResult all, first;
    Collide(a, b, X_AB, req, &all);
    req.first_only = true;
    Collide(a, b, X_AB, req, &first);
    ASSERT_EQ(all.overlap, first.overlap) << trial;
    ASSERT_LE(first.pairs.size(), 1u);
    ASSERT_LE(first.node_tests, all.node_tests);
    hits += all.overlap ? 1 : 0;
  }
  EXPECT_GT(hits, 5);
  EXPECT_LT(hits, 55);
}

TEST_F(CollideOracleTest, BooleanReportsARealPairInEveryMode) {
  // The boolean descends one tree against the other's distance bound (and,
  // with explicit spheres, tests the survivors against the other's voxel
  // occupancy); its pair must be one the full descent reports, at touching
  // (delta 0) and with a tolerance, for every sphere mode.
  std::mt19937 rng(11);
  const SphereTree a = Tree(sphere_, 0.1);
  const SphereTree b = Tree(box_, 0.1);
  int hits = 0;
  for (int trial = 0; trial < 60; ++trial) {
    Eigen::Isometry3d X_AB = RandomPose(rng, 0.6, 3.0);
    X_AB.translation() += Eigen::Vector3d(1.45, 0, 0);
    for (const double delta : {0.0, 0.05}) {
      CollisionRequest req;
      req.delta_mm = delta;
      CollisionResult all;
      Collide(a, b, X_AB, req, &all);
      const std::vector<VoxelPair> pairs = Sorted(all.pairs);
      req.first_only = true;
      for (SphereMode mode : {SphereMode::kSimple, SphereMode::kOptimized, SphereMode::kExplicit}) {
        req.spheres = mode;
        CollisionResult first;
        Collide(a, b, X_AB, req, &first);
        ASSERT_EQ(first.overlap, all.overlap) << trial << " " << ToString(mode);
        ASSERT_EQ(first.pairs.size(), all.overlap ? 1u : 0u);
        if (first.overlap) {
          EXPECT_TRUE(std::binary_search(pairs.begin(), pairs.end(), first.pairs[0]))
              << trial << " " << ToString(mode);
        }
      }
      hits += all.overlap ? 1 : 0;
    }
  }
  EXPECT_GT(hits, 10);
  EXPECT_LT(hits, 110);
}

TEST_F(CollideOracleTest, ExactRefinementMatchesBruteForceMinimumDistance) {
  std::mt19937 rng(77);
  const SphereTree a = Tree(sphere_, 0.12);
  const SphereTree b = Tree(box_, 0.17);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double delta = 0.1;
    Eigen::Isometry3d X_AB = RandomPose(rng, 0.5, 3.0);
    X_AB.translation() += Eigen::Vector3d(1.5, 0, 0);
    CollisionRequest req;
    req.delta_mm = delta;
    req.exact = true;
    CollisionResult res;
    Collide(a, b, X_AB, req, &res);
    const BruteTriangles brute = BruteForceTriangles(a.mesh(), b.mesh(), X_AB, delta);
    ASSERT_EQ(res.contacts.size(), brute.within.size()) << trial;
    if (brute.min_distance <= delta) {
      ++checked;
      ASSERT_NEAR(res.min_distance_mm, brute.min_distance, test::kExactMm) << trial;
      ASSERT_NEAR((res.closest.p_A_on_a - res.closest.p_A_on_b).norm(), res.min_distance_mm, 1e-9);
    } else {
      ASSERT_TRUE(std::isinf(res.min_distance_mm));
    }
    ASSERT_EQ(res.triangles_intersect, brute.min_distance == 0.0);
  }
  EXPECT_GT(checked, 10);
}

TEST_F(CollideOracleTest, ExactAnswerInvariantUnderSharedRigidMotionAndSwap) {
  std::mt19937 rng(99);
  const double delta = 0.08;
  for (int trial = 0; trial < 12; ++trial) {
    Eigen::Isometry3d X_AB = RandomPose(rng, 0.4, 3.0);
    X_AB.translation() += Eigen::Vector3d(1.5, 0, 0);
    const Eigen::Isometry3d G = RandomPose(rng, 20.0, 3.0);
    // Same scene, with both meshes moved by G before the trees are built.
    const SphereTree a = Tree(sphere_, 0.1), b = Tree(box_, 0.1);
    const SphereTree ga = Tree(sphere_.Transformed(G), 0.1), gb = Tree(box_.Transformed(G), 0.1);
    CollisionRequest req;
    req.delta_mm = delta;
    req.exact = true;
    CollisionResult r1, r2, r3;
    Collide(a, b, X_AB, req, &r1);
    Collide(ga, gb, G * X_AB * G.inverse(), req, &r2);
    Collide(b, a, X_AB.inverse(), req, &r3);
    ASSERT_EQ(r1.contacts.size(), r2.contacts.size()) << trial;
    ASSERT_EQ(r1.contacts.size(), r3.contacts.size()) << trial;
    for (std::size_t k = 0; k < r1.contacts.size(); ++k) {
      EXPECT_EQ(r1.contacts[k].triangle_a, r2.contacts[k].triangle_a);
      EXPECT_NEAR(r1.contacts[k].distance_mm, r2.contacts[k].distance_mm, 1e-9);
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> swapped;
    for (const auto& c : r3.contacts) swapped.insert({c.triangle_b, c.triangle_a});
    for (const auto& c : r1.contacts) EXPECT_TRUE(swapped.count({c.triangle_a, c.triangle_b}));
    if (std::isfinite(r1.min_distance_mm)) {
      EXPECT_NEAR(r1.min_distance_mm, r2.min_distance_mm, 1e-9);
      EXPECT_NEAR(r1.min_distance_mm, r3.min_distance_mm, 1e-9);
    }
  }
}

TEST_F(CollideOracleTest, VoxelPairsSymmetricUnderSwap) {
  std::mt19937 rng(8);
  const SphereTree a = Tree(sphere_, 0.1), b = Tree(box_, 0.1);
  for (int trial = 0; trial < 10; ++trial) {
    Eigen::Isometry3d X_AB = RandomPose(rng, 0.4, 3.0);
    X_AB.translation() += Eigen::Vector3d(1.4, 0, 0);
    CollisionRequest req;
    req.delta_mm = 0.05;
    CollisionResult ab, ba;
    Collide(a, b, X_AB, req, &ab);
    Collide(b, a, X_AB.inverse(), req, &ba);
    std::vector<VoxelPair> back;
    for (const auto& p : ba.pairs) back.push_back({p.voxel_b, p.voxel_a});
    EXPECT_EQ(Sorted(ab.pairs), Sorted(back)) << trial;
  }
}

TEST_F(CollideOracleTest, WorkBudgetReportsIncompleteAndFullBudgetCompletes) {
  const SphereTree a = Tree(sphere_, 0.05), b = Tree(sphere_, 0.05);
  Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
  X_AB.translation() = Eigen::Vector3d(1.95, 0.1, 0);
  CollisionRequest req;
  req.delta_mm = 0.1;
  CollisionResult full, cut;
  Collide(a, b, X_AB, req, &full);
  ASSERT_TRUE(full.complete);
  ASSERT_GT(full.node_tests, 100u);
  req.max_node_tests = 50;
  Collide(a, b, X_AB, req, &cut);
  EXPECT_FALSE(cut.complete);
  EXPECT_LE(cut.node_tests, 50u);
  req.max_node_tests = full.node_tests;
  Collide(a, b, X_AB, req, &cut);
  EXPECT_TRUE(cut.complete);
  EXPECT_EQ(cut.pairs.size(), full.pairs.size());
}

TEST(CollideAnalyticTest, FarApartTouchingAndGap) {
  // Binary-exact coordinates, so "touching" is exact.
  const TriangleMesh unit = test::MakeBox({0, 0, 0}, {1, 1, 1});
  const SphereTree a = Tree(unit, 0.125), b = Tree(unit, 0.125);
  Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
  X_AB.translation() = Eigen::Vector3d(10, 0, 0);
  CollisionPair pair(a, b);
  EXPECT_FALSE(pair.Overlap(X_AB));
  // Face to face: exact distance 0, the faces intersect.
  X_AB.translation() = Eigen::Vector3d(1, 0.25, 0);
  CollisionRequest req;
  req.exact = true;
  CollisionResult res;
  pair.Query(X_AB, req, &res);
  EXPECT_TRUE(res.overlap);
  EXPECT_TRUE(res.triangles_intersect);
  EXPECT_EQ(res.min_distance_mm, 0.0);
  // 0.0625 apart: found with delta 0.07, exact distance 0.0625; not found with delta 0.06.
  X_AB.translation() = Eigen::Vector3d(1.0625, 0.25, 0);
  req.delta_mm = 0.07;
  pair.Query(X_AB, req, &res);
  EXPECT_NEAR(res.min_distance_mm, 0.0625, 1e-12);
  EXPECT_FALSE(res.triangles_intersect);
  req.delta_mm = 0.06;
  pair.Query(X_AB, req, &res);
  EXPECT_TRUE(res.contacts.empty());
  EXPECT_TRUE(std::isinf(res.min_distance_mm));
}

TEST(CollideValidationTest, RejectsBadRequests) {
  const TriangleMesh box = test::MakeBox({0, 0, 0}, {1, 1, 1});
  const SphereTree a = Tree(box, 0.2);
  CollisionRequest req;
  CollisionResult res;
  req.delta_mm = -1;
  EXPECT_THROW(Collide(a, a, Eigen::Isometry3d::Identity(), req, &res), std::invalid_argument);
  req.delta_mm = 0;
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() *= 2.0;
  EXPECT_THROW(Collide(a, a, scaled, req, &res), std::invalid_argument);
  Eigen::Isometry3d nan = Eigen::Isometry3d::Identity();
  nan.translation().x() = std::nan("");
  EXPECT_THROW(Collide(a, a, nan, req, &res), std::invalid_argument);
}

TEST(GrownCubesOverlapTest, AxisAlignedIsAnalytic) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_TRUE(GrownCubesOverlap({0, 0, 0}, 0.5, {1.0, 0, 0}, 0.5, I, 0.0));  // touching
  EXPECT_FALSE(GrownCubesOverlap({0, 0, 0}, 0.5, {1.01, 0, 0}, 0.5, I, 0.0));
  EXPECT_TRUE(GrownCubesOverlap({0, 0, 0}, 0.5, {1.01, 0, 0}, 0.5, I, 0.005));
  EXPECT_FALSE(GrownCubesOverlap({0, 0, 0}, 0.5, {1.01, 1.01, 0}, 0.5, I, 0.004));
}

TEST(GrownCubesOverlapTest, RotatedCubesAgreeWithTriangleDistanceOracle) {
  std::mt19937 rng(31);
  int overlaps = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Isometry3d X = RandomPose(rng, 1.2, 3.2);
    const TriangleMesh ca = test::MakeBox({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5});
    const TriangleMesh cb = ca.Transformed(X);
    double dmin = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < 12; ++i) {
      for (std::size_t j = 0; j < 12; ++j) {
        dmin = std::min(dmin,
                        TriangleTriangleDistance(ca.corner(i, 0), ca.corner(i, 1), ca.corner(i, 2),
                                                 cb.corner(j, 0), cb.corner(j, 1), cb.corner(j, 2))
                            .distance);
      }
    }
    const bool contained = X.translation().cwiseAbs().maxCoeff() < 0.5;
    const bool oracle = dmin == 0.0 || contained;
    if (std::abs(dmin) > 1e-9 || oracle) {
      ASSERT_EQ(GrownCubesOverlap({0, 0, 0}, 0.5, X.translation(), 0.5, X.linear(), 0.0), oracle)
          << trial;
    }
    overlaps += oracle ? 1 : 0;
    // Within delta (Euclidean) implies overlap of the cubes grown by delta/2.
    if (dmin <= 0.1) {
      ASSERT_TRUE(GrownCubesOverlap({0, 0, 0}, 0.5, X.translation(), 0.5, X.linear(), 0.05));
    }
  }
  EXPECT_GT(overlaps, 30);
  EXPECT_LT(overlaps, 270);
}

}  // namespace
}  // namespace occlude::collision

namespace occlude::collision {
namespace {

TEST(CollectCellsTest, CoversEveryVoxelPairAndReportsEachCellOnce) {
  std::mt19937 rng(4242);
  const TriangleMesh sphere = test::MakeSphere({0, 0, 0}, 1.0, 10, 14);
  const TriangleMesh box = test::MakeBox({-0.6, -0.4, -0.5}, {0.7, 0.5, 0.3});
  const SphereTree a = Tree(sphere, 0.1), b = Tree(box, 0.1);
  for (int trial = 0; trial < 8; ++trial) {
    Eigen::Isometry3d X_AB = RandomPose(rng, 0.5, 3.0);
    X_AB.translation() += Eigen::Vector3d(1.5, 0, 0);
    const std::vector<VoxelPair> brute = BruteForcePairs(a, b, X_AB, 0.15);
    for (int level : {0, 1, 2}) {
      for (int a_level : {0, 1, 2})
        for (SphereMode mode :
             {SphereMode::kSimple, SphereMode::kOptimized, SphereMode::kExplicit}) {
          CellRequest req;
          req.reach_mm = 0.15;
          req.cell_level = level;
          req.a_level = a_level;
          req.spheres = mode;
          CellResult res;
          CollectCells(a, b, X_AB, req, &res);
          std::set<std::uint64_t> cells;
          for (const auto node : res.cells_b) {
            ASSERT_TRUE(cells.insert(MortonEncode(b.octree().coord[node])).second)
                << "cell reported twice";
          }
          for (const VoxelPair& p : brute) {
            const Eigen::Vector3i v = b.octree().coord[b.octree().leaf_begin() + p.voxel_b];
            const Eigen::Vector3i c(v.x() >> level, v.y() >> level, v.z() >> level);
            ASSERT_TRUE(cells.count(MortonEncode(c))) << "trial " << trial << " level " << level;
          }
        }
    }
  }
}

}  // namespace
}  // namespace occlude::collision
