// The near cells (session/near_cells.h) against brute force: every point within the reach of a
// mesh is near, and a point well beyond it is not, in a bitmap and (a stray triangle far away)
// in the hash set; fixed seeds.
#include "session/near_cells.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "occlude/collision/closest_point.h"

namespace occlude::app {
namespace {

// `count` small triangles (sides up to 0.5 mm) scattered in a 12 mm box, seeded.
io::TriangleMesh ScatteredTriangles(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> where(0.0, 12.0), side(-0.25, 0.25);
  io::TriangleMesh mesh;
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3d c(where(rng), where(rng), where(rng));
    const int first = static_cast<int>(mesh.vertices.size());
    for (int k = 0; k < 3; ++k)
      mesh.vertices.push_back(c + Eigen::Vector3d(side(rng), side(rng), side(rng)));
    mesh.triangles.emplace_back(first, first + 1, first + 2);
  }
  mesh.ComputeFaceNormals();
  return mesh;
}

double BruteDistance(const io::TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    best2 = std::min(best2, collision::ClosestPointOnTriangle(p, mesh.corner(t, 0),
                                                              mesh.corner(t, 1), mesh.corner(t, 2))
                                .squared_distance);
  }
  return std::sqrt(best2);
}

// Points around the mesh's vertices, half at up to 1.2 reaches per axis, half at up to 5, seeded:
// each within the reach must be near; each beyond `far_reaches` reaches (what the cells can span)
// must not be.
void ExpectConservativeAndCulling(const io::TriangleMesh& mesh, const NearCells& cells,
                                  double far_reaches) {
  const double reach = cells.reach_mm();
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> vertex(0, mesh.num_vertices() - 1);
  std::uniform_real_distribution<double> close(-1.2 * reach, 1.2 * reach),
      wide(-5.0 * reach, 5.0 * reach);
  int near = 0, far = 0;
  for (int i = 0; i < 20000; ++i) {
    auto& offset = i % 2 == 0 ? close : wide;
    const Eigen::Vector3d p =
        mesh.vertices[vertex(rng)] + Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
    const double d = BruteDistance(mesh, p);
    if (d <= reach) {
      ASSERT_TRUE(cells.Near(p)) << "point " << p.transpose() << " at " << d << " mm";
      ++near;
    } else if (d > far_reaches * reach) {
      ASSERT_FALSE(cells.Near(p)) << "point " << p.transpose() << " at " << d << " mm";
      ++far;
    }
  }
  EXPECT_GT(near, 500);
  EXPECT_GT(far, 500);
}

TEST(NearCellsTest, BitmapHoldsEveryPointWithinTheReachAndCullsFarOnes) {
  const io::TriangleMesh mesh = ScatteredTriangles(60, 3);
  for (const double reach : {0.4, 1.0, 1.75}) {
    SCOPED_TRACE(reach);
    const NearCells cells(mesh, reach);
    EXPECT_FALSE(cells.hashed());
    EXPECT_EQ(cells.reach_mm(), reach);
    // Half-reach cells grown by two: a near point's cell lies within 3 cells (1.5 reaches) per
    // axis of a triangle's box, 2.6 reaches away at most, plus the triangle's 0.87 mm diagonal.
    ExpectConservativeAndCulling(mesh, cells, 2.7 + 0.9 / reach);
  }
}

TEST(NearCellsTest, HashSetForAStrayTriangleFarAway) {
  io::TriangleMesh mesh = ScatteredTriangles(60, 4);
  // One triangle 5 m away on every axis: the box of cells would be ~10^12 cells.
  const int first = static_cast<int>(mesh.vertices.size());
  for (const Eigen::Vector3d& v :
       {Eigen::Vector3d(5000, 5000, 5000), Eigen::Vector3d(5000.3, 5000, 5000),
        Eigen::Vector3d(5000, 5000.3, 5000)})
    mesh.vertices.push_back(v);
  mesh.triangles.emplace_back(first, first + 1, first + 2);
  mesh.ComputeFaceNormals();
  const NearCells cells(mesh, 1.0);
  EXPECT_TRUE(cells.hashed());
  // Reach cells grown by one: within 2 cells (2 reaches) per axis, 3.5 reaches away at most.
  ExpectConservativeAndCulling(mesh, cells, 3.5 + 0.9);
  EXPECT_TRUE(cells.Near(Eigen::Vector3d(5000.1, 5000.1, 5000.5)));
  EXPECT_FALSE(cells.Near(Eigen::Vector3d(2500, 2500, 2500)));
}

TEST(NearCellsTest, EmptyMeshAndDefaultAreNearNothing) {
  const io::TriangleMesh empty;
  for (const NearCells& cells : {NearCells(), NearCells(empty, 1.0)}) {
    EXPECT_FALSE(cells.Near(Eigen::Vector3d::Zero()));
    EXPECT_FALSE(cells.Near(Eigen::Vector3d(1e6, -1e6, 3.0)));
  }
}

}  // namespace
}  // namespace occlude::app
