// Sphere-tree level statistics, the synthetic jaw pair against brute force,
// concurrent const queries, and surface-proportional voxel counts.
#include "occlude/collision/sphere_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <set>
#include <thread>

#include "occlude/collision/collide.h"
#include "occlude/collision/triangle_triangle.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

SphereTree Build(const io::TriangleMesh& m, double s) {
  SphereTreeOptions o;
  o.voxelize.voxel_size_mm = s;
  return SphereTree::Build(std::make_shared<io::TriangleMesh>(m), o);
}

const io::SyntheticJawPair& SmallJaws() {
  static const io::SyntheticJawPair jaws = [] {
    io::SyntheticJawOptions o;
    o.triangles_per_jaw = 5000;
    o.seed = 3;
    return io::MakeSyntheticJawPair(o);
  }();
  return jaws;
}

TEST(SphereTreeStatsTest, LevelsAddUpAndOptimizedNeverExceedsSimple) {
  const SphereTree t = Build(test::MakeSphere({0, 0, 0}, 5.0, 16, 24), 0.25);
  const SphereTreeStats& st = t.stats();
  ASSERT_EQ(st.levels.size(), static_cast<std::size_t>(t.octree().top_level + 1));
  std::size_t nodes = 0;
  for (const LevelStats& ls : st.levels) {
    nodes += ls.nodes;
    EXPECT_LE(ls.optimized_volume_mm3, ls.simple_volume_mm3 * (1 + 1e-12)) << "level " << ls.level;
    EXPECT_GT(ls.optimized_volume_mm3, 0.0);
  }
  EXPECT_EQ(nodes, st.nodes);
  EXPECT_EQ(st.levels[0].nodes, st.voxelize.surface_voxels);
  EXPECT_EQ(st.levels.back().nodes, 1u);
  EXPECT_GT(st.bytes_grid, 0u);
  EXPECT_GT(st.bytes_octree, 0u);
  EXPECT_GT(st.bytes_explicit, 0u);
}

// Brute force over triangle pairs whose boxes come within delta.
std::vector<std::pair<std::uint32_t, std::uint32_t>> TrianglePairsWithin(
    const io::TriangleMesh& a, const io::TriangleMesh& b_in_a, double delta) {
  auto box = [](const io::TriangleMesh& m, std::size_t t) {
    Eigen::AlignedBox3d bx;
    for (int k = 0; k < 3; ++k) bx.extend(m.corner(t, k));
    return bx;
  };
  std::vector<Eigen::AlignedBox3d> boxes_b;
  for (std::size_t j = 0; j < b_in_a.num_triangles(); ++j) boxes_b.push_back(box(b_in_a, j));
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t i = 0; i < a.num_triangles(); ++i) {
    const Eigen::AlignedBox3d ba = box(a, i);
    for (std::uint32_t j = 0; j < b_in_a.num_triangles(); ++j) {
      if (ba.exteriorDistance(boxes_b[j]) > delta) continue;
      if (TriangleTriangleDistance(a.corner(i, 0), a.corner(i, 1), a.corner(i, 2),
                                   b_in_a.corner(j, 0), b_in_a.corner(j, 1), b_in_a.corner(j, 2))
              .distance <= delta) {
        out.emplace_back(i, j);
      }
    }
  }
  return out;
}

TEST(SyntheticPairQueryTest, ModesAgreeAndNoTrianglePairWithinDeltaIsMissed) {
  const io::SyntheticJawPair& jaws = SmallJaws();
  const SphereTree lower = Build(jaws.lower_L, 0.3), upper = Build(jaws.upper_U, 0.3);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  const double delta = 0.1;
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::Isometry3d jitter = Eigen::Isometry3d::Identity();
    jitter.linear() =
        Eigen::AngleAxisd(0.01 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized())
            .toRotationMatrix();
    jitter.translation() = Eigen::Vector3d(0.1 * u(rng), 0.15 * u(rng) + 0.05, 0.1 * u(rng));
    const Eigen::Isometry3d X_LU = jitter * jaws.X_LU;
    CollisionRequest req;
    req.delta_mm = delta;
    req.exact = true;
    CollisionResult results[3];
    const SphereMode modes[3] = {SphereMode::kSimple, SphereMode::kOptimized,
                                 SphereMode::kExplicit};
    for (int m = 0; m < 3; ++m) {
      req.spheres = modes[m];
      Collide(lower, upper, X_LU, req, &results[m]);
      std::sort(results[m].pairs.begin(), results[m].pairs.end());
    }
    ASSERT_EQ(results[0].pairs, results[1].pairs) << trial;
    ASSERT_EQ(results[0].pairs, results[2].pairs) << trial;
    const auto brute = TrianglePairsWithin(jaws.lower_L, jaws.upper_U.Transformed(X_LU), delta);
    std::set<std::pair<std::uint32_t, std::uint32_t>> found;
    for (const auto& c : results[2].contacts) found.insert({c.triangle_a, c.triangle_b});
    EXPECT_EQ(found.size(), brute.size()) << trial;
    for (const auto& p : brute)
      ASSERT_TRUE(found.count(p)) << "missed " << p.first << "," << p.second;
  }
}

TEST(ConcurrentQueryTest, ThreadsSharingTreesGetIdenticalAnswers) {
  const io::SyntheticJawPair& jaws = SmallJaws();
  const SphereTree lower = Build(jaws.lower_L, 0.3), upper = Build(jaws.upper_U, 0.3);
  const CollisionPair pair(lower, upper);
  CollisionRequest req;
  req.delta_mm = 0.1;
  req.exact = true;
  auto run = [&](std::vector<std::size_t>* out) {
    CollisionResult res;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Isometry3d X = Eigen::Translation3d(0.0, 0.05 * k - 0.1, 0.0) * jaws.X_LU;
      pair.Query(X, req, &res);
      out->push_back(res.pairs.size() * 1000003 + res.contacts.size());
    }
  };
  std::vector<std::size_t> serial, t1, t2;
  run(&serial);
  std::thread a(run, &t1), b(run, &t2);
  a.join();
  b.join();
  EXPECT_EQ(serial, t1);
  EXPECT_EQ(serial, t2);
}

TEST(SyntheticVoxelScalingTest, HalvingTheVoxelQuadruplesTheSurfaceCount) {
  const io::SyntheticJawPair& jaws = SmallJaws();
  VoxelizeOptions coarse, fine;
  coarse.voxel_size_mm = 0.4;
  fine.voxel_size_mm = 0.2;
  coarse.classify_interior = fine.classify_interior = false;
  coarse.classify_proximity = fine.classify_proximity = false;
  const double ratio = static_cast<double>(Voxelize(jaws.lower_L, fine).num_surface()) /
                       static_cast<double>(Voxelize(jaws.lower_L, coarse).num_surface());
  EXPECT_GT(ratio, 3.3);
  EXPECT_LT(ratio, 4.7);
}

}  // namespace
}  // namespace occlude::collision
