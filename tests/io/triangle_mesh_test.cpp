// TriangleMesh helpers: bounds, area, normals, transforms, concatenation.
#include "occlude/io/triangle_mesh.h"

#include <gtest/gtest.h>

#include "test_common.h"

namespace occlude::io {
namespace {

TEST(TriangleMeshTest, BoxAreaBoundsAndOutwardNormals) {
  const TriangleMesh box = test::MakeBox({0, 0, 0}, {1, 2, 3});
  EXPECT_EQ(box.ConsistencyError(), "");
  EXPECT_NEAR(box.SurfaceArea(), 2 * (1 * 2 + 2 * 3 + 1 * 3), 1e-12);
  EXPECT_TRUE(box.Bounds().max().isApprox(Eigen::Vector3d(1, 2, 3)));
  const Eigen::Vector3d centre(0.5, 1, 1.5);
  for (std::size_t t = 0; t < box.num_triangles(); ++t) {
    EXPECT_GT(box.face_normals[t].dot(box.corner(t, 0) - centre), 0.0) << "triangle " << t;
  }
}

TEST(TriangleMeshTest, SphereNormalsPointOutward) {
  const TriangleMesh s = test::MakeSphere({1, 2, 3}, 2.0, 8, 12);
  for (std::size_t t = 0; t < s.num_triangles(); ++t) {
    EXPECT_GT(s.face_normals[t].dot(s.corner(t, 0) - Eigen::Vector3d(1, 2, 3)), 0.0) << t;
  }
}

TEST(TriangleMeshTest, TransformedKeepsAreaAndMovesNormals) {
  const TriangleMesh box = test::MakeBox({0, 0, 0}, {1, 1, 1});
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(5, -1, 2);
  const TriangleMesh moved = box.Transformed(X);
  EXPECT_NEAR(moved.SurfaceArea(), box.SurfaceArea(), 1e-12);
  EXPECT_TRUE(moved.face_normals[3].isApprox(X.linear() * box.face_normals[3]));
}

TEST(TriangleMeshTest, AppendShiftsIndicesAndParts) {
  TriangleMesh a = test::MakeBox({0, 0, 0}, {1, 1, 1});
  const TriangleMesh b = test::MakeBox({2, 0, 0}, {3, 1, 1});
  a.Append(b);
  EXPECT_EQ(a.ConsistencyError(), "");
  EXPECT_EQ(a.parts.size(), 2u);
  EXPECT_EQ(a.triangle_part.back(), 1);
  EXPECT_EQ(a.corner(12, 0), b.corner(0, 0));
}

}  // namespace
}  // namespace occlude::io
