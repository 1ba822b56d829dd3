// The report's rasterizer (report/render_raster.h) against what it must draw: a triangle covers
// exactly the pixel centres inside it (brute force over random triangles, fixed seed), the
// nearer of two surfaces wins whichever is drawn first, a linear field is interpolated exactly,
// and a closed box seen from outside shows the face toward the viewer only.
#include "report/render_raster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "test_common.h"

namespace occlude::app::render {
namespace {

// A view looking along -z of L with x right and y up, 1 px per mm, pixel (0, 0)'s corner at
// (x, y) = (0, height) in L: pixel centre (i + 0.5, j + 0.5) is L's (i + 0.5, height - j - 0.5).
OrthoView PixelView(int width, int height) {
  OrthoView v;
  v.right_L = Eigen::Vector3d::UnitX();
  v.up_L = Eigen::Vector3d::UnitY();
  v.view_L = -Eigen::Vector3d::UnitZ();
  v.px_per_mm = 1.0;
  v.width = width;
  v.height = height;
  v.centre_mm = Eigen::Vector2d(0.5 * width, 0.5 * height);
  return v;
}

io::TriangleMesh OneTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c) {
  io::TriangleMesh m;
  m.vertices = {a, b, c};
  m.triangles = {Eigen::Vector3i(0, 1, 2)};
  return m;
}

// Signed area of the triangle (p, q, r) in the plane z = const (x, y of L).
double Cross(const Eigen::Vector3d& p, const Eigen::Vector3d& q, double x, double y) {
  return (q.x() - p.x()) * (y - p.y()) - (q.y() - p.y()) * (x - p.x());
}

TEST(RasterizeTest, CoversExactlyThePixelCentresInsideATriangle) {
  constexpr int kW = 64, kH = 48;
  const OrthoView view = PixelView(kW, kH);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-8.0, kW + 8.0), y(-8.0, kH + 8.0);
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d a(x(rng), y(rng), 0), b(x(rng), y(rng), 0), c(x(rng), y(rng), 0);
    const double area = Cross(a, b, c.x(), c.y());
    if (std::abs(area) < 1.0) continue;
    const io::TriangleMesh mesh = OneTriangle(a, b, c);
    const GBuffer g = Rasterize(view, {{&mesh, Eigen::Isometry3d::Identity(), nullptr, 0}});
    for (int j = 0; j < kH; ++j) {
      for (int i = 0; i < kW; ++i) {
        const double px = i + 0.5, py = kH - j - 0.5;
        const double wa = Cross(b, c, px, py) / area, wb = Cross(c, a, px, py) / area;
        const double wc = 1.0 - wa - wb;
        const double margin = std::min({wa, wb, wc});
        if (std::abs(margin) < 1e-9) continue;  // on an edge: either answer is right
        const bool drawn = g.id[static_cast<std::size_t>(j * kW + i)] >= 0;
        ASSERT_EQ(drawn, margin > 0) << "trial " << trial << " pixel " << i << "," << j;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 100000);
}

TEST(RasterizeTest, TheNearerSurfaceWinsInEitherDrawingOrder) {
  constexpr int kW = 40, kH = 30;
  const OrthoView view = PixelView(kW, kH);
  // The view looks along -z: larger z is nearer.
  const io::TriangleMesh near = test::MakeBox({5, 5, 4}, {30, 25, 6});
  const io::TriangleMesh far = test::MakeBox({10, 2, -6}, {38, 28, -4});
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  const GBuffer near_first = Rasterize(view, {{&near, I, nullptr, 0}, {&far, I, nullptr, 1}});
  const GBuffer far_first = Rasterize(view, {{&far, I, nullptr, 1}, {&near, I, nullptr, 0}});
  int near_pixels = 0;
  for (int j = 0; j < kH; ++j) {
    for (int i = 0; i < kW; ++i) {
      const auto k = static_cast<std::size_t>(j * kW + i);
      EXPECT_EQ(near_first.id[k], far_first.id[k]) << i << "," << j;
      EXPECT_EQ(near_first.depth[k], far_first.depth[k]) << i << "," << j;
      const double px = i + 0.5, py = kH - j - 0.5;
      if (px > 5 && px < 30 && py > 5 && py < 25) {
        EXPECT_EQ(near_first.id[k], 0) << i << "," << j;
        EXPECT_FLOAT_EQ(near_first.depth[k], -6.0f);  // depth = p . view = -z of the top face
        ++near_pixels;
      }
    }
  }
  EXPECT_EQ(near_pixels, 25 * 20);
}

TEST(RasterizeTest, InterpolatesALinearFieldExactly) {
  constexpr int kW = 50, kH = 40;
  const OrthoView view = PixelView(kW, kH);
  io::TriangleMesh mesh = OneTriangle({1, 1, 0}, {49, 3, 0}, {20, 39, 0});
  std::vector<float> value;  // 0.25 x - 0.5 y + 3 at each vertex
  for (const auto& p : mesh.vertices)
    value.push_back(static_cast<float>(0.25 * p.x() - 0.5 * p.y() + 3));
  const GBuffer g = Rasterize(view, {{&mesh, Eigen::Isometry3d::Identity(), &value, 0}});
  int covered = 0;
  for (int j = 0; j < kH; ++j) {
    for (int i = 0; i < kW; ++i) {
      const auto k = static_cast<std::size_t>(j * kW + i);
      if (g.id[k] < 0) continue;
      const double px = i + 0.5, py = kH - j - 0.5;
      EXPECT_NEAR(g.value[k], 0.25 * px - 0.5 * py + 3, 1e-4) << i << "," << j;
      ++covered;
    }
  }
  EXPECT_GT(covered, 500);
}

TEST(RasterizeTest, AClosedBoxShowsItsFrontFacesOnly) {
  constexpr int kW = 40, kH = 30;
  const OrthoView view = PixelView(kW, kH);
  const io::TriangleMesh box = test::MakeBox({5, 5, -5}, {35, 25, 5});
  const GBuffer g = Rasterize(view, {{&box, Eigen::Isometry3d::Identity(), nullptr, 0}});
  // Every pixel drawn shows the face toward the viewer (z = 5: depth -5), none of the five
  // behind it, whatever order the triangles come in.
  int drawn = 0;
  for (std::size_t k = 0; k < g.id.size(); ++k) {
    if (g.id[k] < 0) continue;
    EXPECT_FLOAT_EQ(g.depth[k], -5.0f) << k;
    ++drawn;
  }
  EXPECT_EQ(drawn, 30 * 20);
}

}  // namespace
}  // namespace occlude::app::render
