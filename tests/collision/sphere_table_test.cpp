// Implicit-sphere geometry: the child offset derivation (the paper's s*2^(L-1)
// versus its source's s*2^(L-2)) and the optimized-sphere lookup table.
#include "occlude/collision/sphere_table.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <vector>

namespace occlude::collision {
namespace {

constexpr double kTol = 1e-12;

std::vector<Eigen::Vector3d> CubeCorners(const Eigen::Vector3d& center, double edge) {
  std::vector<Eigen::Vector3d> c;
  for (int k = 0; k < 8; ++k) c.push_back(center + 0.5 * edge * ChildSlotSign(k));
  return c;
}

// Node cube centre from integer node coordinates, as the octree defines it.
Eigen::Vector3d NodeCenter(const Eigen::Vector3i& coord, int level, double s) {
  return std::ldexp(s, level) * (coord.cast<double>() + Eigen::Vector3d::Constant(0.5));
}

TEST(SphereTableTest, ChildOffsetIsAQuarterOfTheParentEdge) {
  for (double s : {0.1, 0.2, 1.0}) {
    for (int parent_level = 1; parent_level <= 8; ++parent_level) {
      const Eigen::Vector3i parent(3, 5, 7);
      const Eigen::Vector3d pc = NodeCenter(parent, parent_level, s);
      const double parent_r = SimpleRadius(std::ldexp(s, parent_level));
      for (int slot = 0; slot < 8; ++slot) {
        const Eigen::Vector3i child =
            2 * parent + Eigen::Vector3i(slot & 1, (slot >> 1) & 1, (slot >> 2) & 1);
        const Eigen::Vector3d truth = NodeCenter(child, parent_level - 1, s);
        const Eigen::Vector3d derived =
            pc + ChildCenterOffset(s, parent_level) * ChildSlotSign(slot);
        ASSERT_LT((derived - truth).norm(), kTol * std::ldexp(s, parent_level));
        const double child_edge = std::ldexp(s, parent_level - 1);
        for (const auto& corner : CubeCorners(derived, child_edge)) {
          // Every child sphere contains its child cube ...
          EXPECT_LE((corner - derived).norm(), SimpleRadius(child_edge) + kTol);
          // ... and every child cube lies inside the parent sphere.
          EXPECT_LE((corner - pc).norm(), parent_r + kTol);
        }
      }
    }
  }
}

TEST(SphereTableTest, ParentLevelOffsetSTimes2ToLMinus1PutsChildrenOnParentCorners) {
  // With L the parent's level, s*2^(L-1) is half the parent edge: the "child"
  // centre lands on a corner of the parent cube, so the child cube pokes out of
  // the parent sphere. The paper's formula is right only with L = child level.
  const double s = 0.2;
  const int parent_level = 3;
  const Eigen::Vector3d pc = NodeCenter({0, 0, 0}, parent_level, s);
  const Eigen::Vector3d wrong = pc + std::ldexp(s, parent_level - 1) * ChildSlotSign(7);
  const double child_edge = std::ldexp(s, parent_level - 1);
  double farthest = 0.0;
  for (const auto& corner : CubeCorners(wrong, child_edge))
    farthest = std::max(farthest, (corner - pc).norm());
  EXPECT_GT(farthest, SimpleRadius(std::ldexp(s, parent_level)) * 1.4);
  // Same offset written with the child's level is the correct one.
  EXPECT_DOUBLE_EQ(std::ldexp(s, (parent_level - 1) - 1), ChildCenterOffset(s, parent_level));
}

std::vector<Eigen::Vector3d> OccupiedCorners(int mask) {
  std::vector<Eigen::Vector3d> pts;
  for (int slot = 0; slot < 8; ++slot) {
    if (!(mask & (1 << slot))) continue;
    for (const auto& c : CubeCorners(0.25 * ChildSlotSign(slot), 0.5)) pts.push_back(c);
  }
  return pts;
}

TEST(SphereTableTest, EveryEntryEnclosesItsOccupiedChildCubesAndIsNoLargerThanSimple) {
  const auto& table = OptimizedSphereTable();
  EXPECT_NEAR(table[0].radius, kCubeCircumradius, kTol);
  for (int mask = 1; mask < 256; ++mask) {
    const UnitSphere& u = table[static_cast<std::size_t>(mask)];
    for (const auto& p : OccupiedCorners(mask)) {
      ASSERT_LE((p - u.center).norm(), u.radius + 1e-12) << "mask " << mask;
    }
    EXPECT_LE(u.radius, kCubeCircumradius + kTol) << "mask " << mask;
  }
  EXPECT_NEAR(table[1].radius, kCubeCircumradius / 2, kTol);  // one child: its own circumsphere
  EXPECT_NEAR(table[255].radius, kCubeCircumradius, kTol);    // all children: the simple sphere
  EXPECT_NEAR(table[3].radius, std::sqrt(1.0 + 0.25 + 0.25) / 2,
              kTol);  // two along x: 1 x 1/2 x 1/2 box
}

// Smallest enclosing ball by brute force over all 2-, 3- and 4-point supports.
double BruteForceMinRadius(const std::vector<Eigen::Vector3d>& pts) {
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](const Eigen::Vector3d& c) {
    double r = 0.0;
    for (const auto& p : pts) r = std::max(r, (p - c).norm());
    best = std::min(best, r);
  };
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      consider(0.5 * (pts[i] + pts[j]));
      for (std::size_t k = j + 1; k < n; ++k) {
        const Eigen::Vector3d ab = pts[j] - pts[i], ac = pts[k] - pts[i], nn = ab.cross(ac);
        if (nn.squaredNorm() < 1e-20) continue;
        consider(pts[i] + (ac.squaredNorm() * nn.cross(ab) + ab.squaredNorm() * ac.cross(nn)) /
                              (2 * nn.squaredNorm()));
        for (std::size_t l = k + 1; l < n; ++l) {
          Eigen::Matrix3d m;
          m << (pts[j] - pts[i]).transpose(), (pts[k] - pts[i]).transpose(),
              (pts[l] - pts[i]).transpose();
          if (std::abs(m.determinant()) < 1e-12) continue;
          const Eigen::Vector3d rhs(0.5 * m.row(0).squaredNorm(), 0.5 * m.row(1).squaredNorm(),
                                    0.5 * m.row(2).squaredNorm());
          consider(pts[i] + m.partialPivLu().solve(rhs));
        }
      }
    }
  }
  return best;
}

TEST(SphereTableTest, EntriesAreMinimal) {
  const auto& table = OptimizedSphereTable();
  for (int mask = 1; mask < 256; mask += 3) {  // a third of the masks keeps this fast
    std::vector<Eigen::Vector3d> pts = OccupiedCorners(mask);
    std::sort(pts.begin(), pts.end(), [](const auto& x, const auto& y) {
      return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
    });
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    EXPECT_NEAR(table[static_cast<std::size_t>(mask)].radius, BruteForceMinRadius(pts), 1e-9)
        << "mask " << mask;
  }
}

}  // namespace
}  // namespace occlude::collision
