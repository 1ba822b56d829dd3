// DistanceBound against brute force: never above the exact distance to the
// union of surface voxel cubes, exact at cell centres below the cap, and
// Excludes consistent with it; and the bound-based one-sided CollectCells
// covering every upper surface point within reach.
#include "occlude/collision/distance_bound.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "occlude/collision/closest_point.h"
#include "occlude/collision/collide.h"
#include "occlude/collision/morton.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

using V = Eigen::Vector3d;

VoxelGrid Grid(const io::TriangleMesh& m, double s) {
  VoxelizeOptions o;
  o.voxel_size_mm = s;
  o.classify_proximity = false;
  o.classify_interior = false;
  return Voxelize(m, o);
}

// Exact distance from p to the union of the grid's surface voxel cubes.
double BruteDistance(const VoxelGrid& g, const V& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const std::uint64_t k : g.surface_keys) {
    const V gap = ((p - g.VoxelCenter(MortonDecode(k))).cwiseAbs().array() - 0.5 * g.voxel_size_mm)
                      .cwiseMax(0.0);
    best = std::min(best, gap.norm());
  }
  return best;
}

// Rounding allowance of the bound (mm-sized inputs).
constexpr double kBoundSlackMm = 1e-9;

TEST(DistanceBoundTest, NeverAboveTheExactDistanceAndExactAtCellCentres) {
  io::TriangleMesh mesh = test::MakeSphere(V(0, 0, 0), 1.2, 12, 18);
  mesh.Append(test::MakeBox(V(0.9, -0.3, -0.2), V(2.0, 0.4, 0.5)));
  const double s = 0.1;
  const VoxelGrid grid = Grid(mesh, s);
  const DistanceBound bound = DistanceBound::Build(grid);
  ASSERT_FALSE(bound.empty());
  EXPECT_NEAR(bound.max_mm(), 7.5 * s * 8, 1e-9);  // coarsest level 3: cells of 8 s
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3.5, 3.5);
  int exact_centres = 0;
  for (int i = 0; i < 3000; ++i) {
    V p(u(rng), u(rng), u(rng));
    if (i % 2 == 0) {  // a voxel centre
      const V q = (p - grid.origin_F) / s;
      p = grid.origin_F +
          s * (V(std::floor(q.x()), std::floor(q.y()), std::floor(q.z())) + V::Constant(0.5));
    }
    const double exact = BruteDistance(grid, p);
    const double lb = bound.LowerBound(p);
    ASSERT_LE(lb, exact + kBoundSlackMm) << p.transpose();
    if (i % 2 == 0 && exact < 7.0 * s) {
      EXPECT_NEAR(lb, exact, 1e-9) << p.transpose();
      ++exact_centres;
    }
    for (const double r : {0.0, 0.05, 0.2, 0.5}) {
      if (bound.Excludes(p, r)) {
        ASSERT_GT(exact, r) << p.transpose();
      }
    }
  }
  EXPECT_GT(exact_centres, 100);
  EXPECT_FALSE(bound.Excludes(V(std::nan(""), 0, 0), 0.0));
  EXPECT_TRUE(std::isinf(DistanceBound().LowerBound(V(0, 0, 0))));
  EXPECT_THROW(DistanceBound::Build(grid, 0), std::invalid_argument);
  EXPECT_THROW(DistanceBound::Build(grid, 3, {2, 1}), std::invalid_argument);
}

// A grid handed over (the oracle's field bound) gives the same bound, reads alike everywhere,
// and its keys are gone afterwards.
TEST(DistanceBoundTest, AConsumedGridGivesTheSameBound) {
  io::TriangleMesh mesh = test::MakeSphere(V(0, 0, 0), 1.2, 12, 18);
  mesh.Append(test::MakeBox(V(0.9, -0.3, -0.2), V(2.0, 0.4, 0.5)));
  const VoxelGrid grid = Grid(mesh, 0.1);
  const DistanceBound kept = DistanceBound::Build(grid, 5, {0, 1, 2, 4});
  VoxelGrid handed = grid;
  const DistanceBound consumed = DistanceBound::Build(std::move(handed), 5, {0, 1, 2, 4});
  EXPECT_TRUE(handed.surface_keys.empty());  // NOLINT(bugprone-use-after-move): it is reset
  EXPECT_EQ(kept.MemoryBytes(), consumed.MemoryBytes());
  EXPECT_EQ(kept.max_mm(), consumed.max_mm());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 2000; ++i) {
    const V p(u(rng), u(rng), u(rng));
    ASSERT_EQ(kept.LowerBound(p), consumed.LowerBound(p)) << p.transpose();
  }
}

TEST(DistanceBoundTest, OneSidedCellsCoverEverySurfacePointWithinReach) {
  const io::TriangleMesh sphere = test::MakeSphere({0, 0, 0}, 1.0, 10, 14);
  const io::TriangleMesh box = test::MakeBox({-0.6, -0.4, -0.5}, {0.7, 0.5, 0.3});
  SphereTreeOptions o;
  o.voxelize.voxel_size_mm = 0.1;
  const SphereTree a = SphereTree::Build(std::make_shared<const io::TriangleMesh>(sphere), o);
  const SphereTree b = SphereTree::Build(std::make_shared<const io::TriangleMesh>(box), o);
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  constexpr double kReach = 0.15;
  int checked = 0;
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
    X_AB.linear() =
        Eigen::AngleAxisd(2.0 * u(rng), V(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    X_AB.translation() = V(1.4 + 0.3 * u(rng), 0.2 * u(rng), 0.1 * u(rng));
    for (const int level : {0, 1, 2}) {
      for (const SphereMode mode :
           {SphereMode::kSimple, SphereMode::kOptimized, SphereMode::kExplicit}) {
        CellRequest req;
        req.reach_mm = kReach;
        req.cell_level = level;
        req.spheres = mode;
        req.distance_bound = true;
        CellResult res;
        CollectCells(a, b, X_AB, req, &res);
        std::set<std::uint64_t> cells;
        for (const auto node : res.cells_b) {
          ASSERT_TRUE(cells.insert(MortonEncode(b.octree().coord[node])).second)
              << "cell reported twice";
        }
        // Random points on B's triangles within reach of A's surface.
        for (int i = 0; i < 400; ++i) {
          const std::size_t t = rng() % box.num_triangles();
          double x = u(rng), y = u(rng);
          if (x + y > 1) {
            x = 1 - x;
            y = 1 - y;
          }
          const V p_B = box.corner(t, 0) + x * (box.corner(t, 1) - box.corner(t, 0)) +
                        y * (box.corner(t, 2) - box.corner(t, 0));
          const V p_A = X_AB * p_B;
          double d2 = std::numeric_limits<double>::infinity();
          for (std::size_t k = 0; k < sphere.num_triangles(); ++k) {
            d2 = std::min(d2, ClosestPointOnTriangle(p_A, sphere.corner(k, 0), sphere.corner(k, 1),
                                                     sphere.corner(k, 2))
                                  .squared_distance);
          }
          if (d2 > kReach * kReach) continue;
          const Eigen::Vector3i v = b.grid().VoxelOf(p_B);
          ++checked;
          const Eigen::Vector3i c(v.x() >> level, v.y() >> level, v.z() >> level);
          ASSERT_TRUE(cells.count(MortonEncode(c))) << "trial " << trial << " level " << level;
        }
      }
    }
  }
  EXPECT_GT(checked, 50);
}

// CellRequest::b_spheres: the caller's spheres (here: of random points on B's
// surface, as the oracle's samples) replace B's; every such point within reach
// of A's surface lies in a reported cell, and a node without points is never
// reported.
TEST(DistanceBoundTest, CallerSpheresCoverTheirPointsWithinReach) {
  const io::TriangleMesh sphere = test::MakeSphere({0, 0, 0}, 1.0, 10, 14);
  const io::TriangleMesh box = test::MakeBox({-0.6, -0.4, -0.5}, {0.7, 0.5, 0.3});
  SphereTreeOptions o;
  o.voxelize.voxel_size_mm = 0.1;
  const SphereTree a = SphereTree::Build(std::make_shared<const io::TriangleMesh>(sphere), o);
  const SphereTree b = SphereTree::Build(std::make_shared<const io::TriangleMesh>(box), o);
  const Octree& oct = b.octree();
  std::mt19937 rng(78);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Points on B's triangles, only on the faces x = -0.6 and z = 0.3 (so that some
  // nodes hold none), and per node of levels >= 1 their bounding sphere.
  std::vector<V> points;
  while (points.size() < 3000) {
    const std::size_t t = rng() % box.num_triangles();
    double x = u(rng), y = u(rng);
    if (x + y > 1) {
      x = 1 - x;
      y = 1 - y;
    }
    const V p = box.corner(t, 0) + x * (box.corner(t, 1) - box.corner(t, 0)) +
                y * (box.corner(t, 2) - box.corner(t, 0));
    if (std::abs(p.x() + 0.6) < 1e-9 || std::abs(p.z() - 0.3) < 1e-9) points.push_back(p);
  }
  std::vector<std::vector<V>> in_node(oct.num_nodes());
  for (const V& p : points) {
    const Eigen::Vector3i v = b.grid().VoxelOf(p);
    for (int level = 1; level <= oct.top_level; ++level) {
      const Eigen::Vector3i c(v.x() >> level, v.y() >> level, v.z() >> level);
      for (auto n = oct.level_begin[static_cast<std::size_t>(level)];
           n < oct.level_end[static_cast<std::size_t>(level)]; ++n) {
        if (oct.coord[n] == c) in_node[n].push_back(p);
      }
    }
  }
  std::vector<Eigen::Vector4f> spheres(oct.num_nodes(), Eigen::Vector4f(0, 0, 0, -1));
  for (std::size_t n = 0; n < oct.num_nodes(); ++n) {
    if (in_node[n].empty()) continue;
    V c = V::Zero();
    for (const V& p : in_node[n]) c += p / static_cast<double>(in_node[n].size());
    double r = 0;
    for (const V& p : in_node[n]) r = std::max(r, (p - c.cast<float>().cast<double>()).norm());
    spheres[n] << c.cast<float>(), static_cast<float>(r + 1e-6);
  }
  constexpr double kReach = 0.15;
  int checked = 0, empty_nodes = 0;
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::Isometry3d X_AB = Eigen::Isometry3d::Identity();
    X_AB.linear() =
        Eigen::AngleAxisd(2.0 * u(rng), V(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
    X_AB.translation() = V(1.4 + 0.3 * u(rng), 0.2 * u(rng), 0.1 * u(rng));
    for (const int level : {1, 2}) {
      CellRequest req;
      req.reach_mm = kReach;
      req.cell_level = level;
      req.distance_bound = true;
      req.b_spheres = spheres.data();
      CellResult res;
      CollectCells(a, b, X_AB, req, &res);
      std::set<std::uint32_t> cells(res.cells_b.begin(), res.cells_b.end());
      ASSERT_EQ(cells.size(), res.cells_b.size()) << "cell reported twice";
      for (const auto node : res.cells_b)
        EXPECT_FALSE(in_node[node].empty()) << "node without points reported";
      for (auto n = oct.level_begin[static_cast<std::size_t>(level)];
           n < oct.level_end[static_cast<std::size_t>(level)]; ++n) {
        if (in_node[n].empty()) {
          ++empty_nodes;
          continue;
        }
        for (const V& p_B : in_node[n]) {
          const V p_A = X_AB * p_B;
          double d2 = std::numeric_limits<double>::infinity();
          for (std::size_t k = 0; k < sphere.num_triangles(); ++k) {
            d2 = std::min(d2, ClosestPointOnTriangle(p_A, sphere.corner(k, 0), sphere.corner(k, 1),
                                                     sphere.corner(k, 2))
                                  .squared_distance);
          }
          if (d2 > kReach * kReach) continue;
          ++checked;
          ASSERT_TRUE(cells.count(n)) << "trial " << trial << " level " << level;
        }
      }
    }
  }
  EXPECT_GT(checked, 50);
  EXPECT_GT(empty_nodes, 0);
}

}  // namespace
}  // namespace occlude::collision
