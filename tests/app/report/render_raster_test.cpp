// The report's rasterizer (report/render_raster.h) against what it must draw: a triangle covers
// exactly the pixel centres inside it (brute force over random triangles, fixed seed), the
// nearer of two surfaces wins whichever is drawn first, a pile of random front and back faces
// shows the nearest at every pixel (brute force: the hidden back faces the rasterizer skips
// would not have shown), a linear field is interpolated exactly, and a closed box seen from
// outside shows the face toward the viewer only.
#include "report/render_raster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
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

// Rasterizes triangle (a, b, c) (in the plane z = 0 of a PixelView) and checks every pixel
// against brute force: drawn exactly when its centre is inside (pixels within 1e-9 of an edge,
// in barycentric weight, are left out: either answer is right there); counts those checked.
void ExpectCoversThePixelCentresInside(const OrthoView& view, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                       int trial, int* checked) {
  const double area = Cross(a, b, c.x(), c.y());
  const io::TriangleMesh mesh = OneTriangle(a, b, c);
  const GBuffer g = Rasterize(view, {{&mesh, Eigen::Isometry3d::Identity(), nullptr, 0}});
  for (int j = 0; j < view.height; ++j) {
    for (int i = 0; i < view.width; ++i) {
      const double px = i + 0.5, py = view.height - j - 0.5;
      const double wa = Cross(b, c, px, py) / area, wb = Cross(c, a, px, py) / area;
      const double margin = std::min({wa, wb, 1.0 - wa - wb});
      if (std::abs(margin) < 1e-9) continue;
      const bool drawn = g.id[static_cast<std::size_t>(j * view.width + i)] >= 0;
      ASSERT_EQ(drawn, margin > 0) << "trial " << trial << " pixel " << i << "," << j;
      ++*checked;
    }
  }
}

TEST(RasterizeTest, CoversExactlyThePixelCentresInsideATriangle) {
  constexpr int kW = 64, kH = 48;
  const OrthoView view = PixelView(kW, kH);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(-8.0, kW + 8.0), y(-8.0, kH + 8.0);
  int checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d a(x(rng), y(rng), 0), b(x(rng), y(rng), 0), c(x(rng), y(rng), 0);
    if (std::abs(Cross(a, b, c.x(), c.y())) < 1.0) continue;
    ASSERT_NO_FATAL_FAILURE(ExpectCoversThePixelCentresInside(view, a, b, c, trial, &checked));
  }
  EXPECT_GT(checked, 100000);
}

// Slivers and triangles with nearly horizontal or vertical edges (slopes down to 1e-9), whose
// rows' spans the rasterizer finds through the edges' inverse slopes: the pixel centres
// inside, no more, no fewer.
TEST(RasterizeTest, CoversThePixelCentresOfSliversAndNearlyFlatEdges) {
  constexpr int kW = 64, kH = 48;
  const OrthoView view = PixelView(kW, kH);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> x(-4.0, kW + 4.0), y(-4.0, kH + 4.0), unit(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector3d a(x(rng), y(rng), 0);
    Eigen::Vector3d b(x(rng), y(rng), 0), c(x(rng), y(rng), 0);
    const double tiny = std::pow(10.0, -9.0 * unit(rng));  // 1e-9 .. 1
    switch (trial % 3) {
      case 0:  // a nearly horizontal edge a-b
        b.y() = a.y() + tiny * (b.x() - a.x());
        break;
      case 1:  // a nearly vertical edge a-c
        c.x() = a.x() + tiny * (c.y() - a.y());
        break;
      default:  // a sliver: c close to the line a-b
        c = a + unit(rng) * (b - a) + Eigen::Vector3d(-(b - a).y(), (b - a).x(), 0) * tiny;
    }
    if (std::abs(Cross(a, b, c.x(), c.y())) < 1e-6) continue;
    ASSERT_NO_FATAL_FAILURE(ExpectCoversThePixelCentresInside(view, a, b, c, trial, &checked));
  }
  EXPECT_GT(checked, 100000);
}

// Random triangles at random depths and tilts, half of them turned away from the viewer, in
// one mesh and split over two: every pixel shows the nearest triangle over its centre (its
// depth, and the darker shade when it faces away), none where none covers it.
TEST(RasterizeTest, APileOfFrontAndBackFacesShowsTheNearestEverywhere) {
  constexpr int kW = 60, kH = 44;
  const OrthoView view = PixelView(kW, kH);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> x(-5.0, kW + 5.0), y(-5.0, kH + 5.0), z(-20.0, 20.0);
  io::TriangleMesh pile, first, second;
  int added = 0;
  const auto add = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                       const Eigen::Vector3d& c) {
    for (io::TriangleMesh* m : {&pile, added++ % 2 == 0 ? &first : &second}) {
      const int base = static_cast<int>(m->vertices.size());
      m->vertices.insert(m->vertices.end(), {a, b, c});
      m->triangles.emplace_back(base, base + 1, base + 2);
    }
  };
  // A wall facing the viewer behind everything, so that every block is covered after the front
  // faces; then back faces just in front of it (0.1-0.4 mm: they must show), others behind it
  // (hidden), and random triangles of both kinds at random depths and tilts.
  add({-10, -10, -30}, {kW + 10, -10, -30}, {kW + 10, kH + 10, -30});
  add({-10, -10, -30}, {kW + 10, kH + 10, -30}, {-10, kH + 10, -30});
  std::uniform_real_distribution<double> just_in_front(-29.9, -29.6), behind(-40.0, -31.0);
  for (int t = 0; t < 240; ++t) {
    Eigen::Vector3d a(x(rng), y(rng), z(rng)), b(x(rng), y(rng), z(rng)), c(x(rng), y(rng), z(rng));
    if (std::abs(Cross(a, b, c.x(), c.y())) < 4.0) continue;
    if (t % 3 != 0) {  // a back face near the wall: flat, clockwise seen from the viewer
      if (Cross(a, b, c.x(), c.y()) > 0) std::swap(b, c);
      const double at = t % 3 == 1 ? just_in_front(rng) : behind(rng);
      a.z() = b.z() = c.z() = at;
    }
    add(a, b, c);
  }
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  const GBuffer one = Rasterize(view, {{&pile, I, nullptr, 0}});
  const GBuffer two = Rasterize(view, {{&first, I, nullptr, 0}, {&second, I, nullptr, 1}});
  int covered = 0, back = 0;
  for (int j = 0; j < kH; ++j) {
    for (int i = 0; i < kW; ++i) {
      const double px = i + 0.5, py = kH - j - 0.5;
      // Brute force: the nearest (largest z) triangle over the pixel centre.
      double nearest = -std::numeric_limits<double>::infinity(), second_nearest = nearest;
      bool near_edge = false, nearest_back = false;
      for (const auto& tri : pile.triangles) {
        const Eigen::Vector3d &a = pile.vertices[static_cast<std::size_t>(tri[0])],
                              &b = pile.vertices[static_cast<std::size_t>(tri[1])],
                              &c = pile.vertices[static_cast<std::size_t>(tri[2])];
        const double area = Cross(a, b, c.x(), c.y());
        const double wa = Cross(b, c, px, py) / area, wb = Cross(c, a, px, py) / area;
        const double wc = 1.0 - wa - wb;
        if (std::abs(std::min({wa, wb, wc})) < 1e-7) near_edge = true;
        if (std::min({wa, wb, wc}) <= 0) continue;
        const double zp = wa * a.z() + wb * b.z() + wc * c.z();
        if (zp > nearest) {
          second_nearest = nearest;
          nearest = zp;
          nearest_back = area < 0;  // clockwise seen from +z: turned away from the viewer
        } else {
          second_nearest = std::max(second_nearest, zp);
        }
      }
      if (near_edge || nearest - second_nearest < 1e-4) continue;  // ambiguous pixel
      const auto k = static_cast<std::size_t>(j * kW + i);
      for (const GBuffer* g : {&one, &two}) {
        if (!std::isfinite(nearest)) {
          EXPECT_LT(g->id[k], 0) << i << "," << j;
          continue;
        }
        ASSERT_GE(g->id[k], 0) << i << "," << j;
        EXPECT_NEAR(g->depth[k], -nearest, 1e-4) << i << "," << j;  // depth = p . view = -z
      }
      if (std::isfinite(nearest)) {
        ++covered;
        back += nearest_back ? 1 : 0;
        // A face turned away is drawn at most kBackFaceDim (0.55) as bright as the full shade.
        if (nearest_back) {
          EXPECT_LE(one.shade[k], 0.55f + 1e-6f) << i << "," << j;
        }
      }
    }
  }
  EXPECT_GT(covered, 2000);
  EXPECT_GT(back, 500);  // back faces showing: the skipping must not hide them
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
