// The report's z-buffered rasterizer (see render_raster.h).
#include "report/render_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "occlude/collision/floor_int.h"

namespace occlude::app::render {
namespace {

constexpr float kAmbient = 0.28f;
constexpr float kBackFaceDim = 0.55f;

struct Vertex2 {
  double x, y, depth;
  float value;
  Eigen::Vector3f n;
};

using collision::detail::FloorInt;
int CeilInt(double x) { return -FloorInt(-x); }

// The pixels DrawTriangle may test for (a, b, c): its vertices' box widened to whole pixels,
// clipped to the image (empty when x0 > x1 or y0 > y1).
struct PixelBox {
  int x0, x1, y0, y1;
};

PixelBox BoxOf(const Vertex2& a, const Vertex2& b, const Vertex2& c, int width, int height) {
  return {std::max(0, FloorInt(std::min({a.x, b.x, c.x}))),
          std::min(width - 1, CeilInt(std::max({a.x, b.x, c.x}))),
          std::max(0, FloorInt(std::min({a.y, b.y, c.y}))),
          std::min(height - 1, CeilInt(std::max({a.y, b.y, c.y})))};
}

double Edge(const Vertex2& a, const Vertex2& b, double px, double py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

// A barycentric weight as an affine function of the pixel centre (px, py), with 1 / x (0 when
// x is 0) for the rows' spans.
struct Weight {
  double x = 0, y = 0, k = 0;
  double inv_x = 0;
  double At(double px, double py) const { return x * px + y * py + k; }
  Weight& WithInverse() {
    inv_x = x != 0.0 ? 1.0 / x : 0.0;
    return *this;
  }
};

// The weight of the vertex opposite the edge p -> q: Edge(p, q, px, py) / area.
Weight OppositeWeight(const Vertex2& p, const Vertex2& q, double inv_area) {
  return {-(q.y - p.y) * inv_area, (q.x - p.x) * inv_area,
          ((q.y - p.y) * p.x - (q.x - p.x) * p.y) * inv_area};
}

// Narrows [lo, hi] (pixel-centre x) towards where w >= 0 along the row at py (up to the
// rounding SpanSlack bounds); false when w is negative all along it.
bool ClipSpan(const Weight& w, double py, double* lo, double* hi) {
  const double r = w.y * py + w.k;
  if (w.x > 0) {
    *lo = std::max(*lo, -r * w.inv_x);
  } else if (w.x < 0) {
    *hi = std::min(*hi, -r * w.inv_x);
  } else if (r < 0) {
    return false;
  }
  return true;
}

// How far (pixels) a span's end found by ClipSpan may lie from where the per-pixel weights
// (ua, ub and uc = 1 - ua - ub, summed in another order) change sign: their rounding, bounded
// far above by 1e-9 of each weight's terms over its slope along the row (the product with the
// slope's inverse included); at most a pixel (a weight all but constant along rows, whose end
// the product cannot place).
double SpanSlack(const Weight& wa, const Weight& wb, const Weight& wc, int width, int height) {
  const auto terms = [&](const Weight& w) {
    return std::abs(w.x) * (width + 1.0) + std::abs(w.y) * (height + 1.0) + std::abs(w.k);
  };
  const double ta = terms(wa), tb = terms(wb);
  double slack = 0.0;
  for (const auto& [w, t] : {std::pair{wa, ta}, std::pair{wb, tb}, std::pair{wc, ta + tb + 1.0}}) {
    slack = std::max(slack, 1e-9 * t * std::abs(w.inv_x));
  }
  return std::min(1.0, slack);
}

void DrawTriangle(const Vertex2& a, const Vertex2& b, const Vertex2& c, bool back_face,
                  const Eigen::Vector3f& light, std::int16_t id, GBuffer* g) {
  const double area = Edge(a, b, c.x, c.y);
  if (std::abs(area) < 1e-12) return;
  const double inv_area = 1.0 / area;
  const Weight wa = OppositeWeight(b, c, inv_area).WithInverse();
  const Weight wb = OppositeWeight(c, a, inv_area).WithInverse();
  const Weight wc = Weight{-(wa.x + wb.x), -(wa.y + wb.y), 1.0 - wa.k - wb.k}.WithInverse();
  const double slack = SpanSlack(wa, wb, wc, g->width, g->height);
  const auto [x0, x1, y0, y1] = BoxOf(a, b, c, g->width, g->height);
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    // The row's pixel centres inside the triangle, found from its three edges and widened by
    // the slack each way (a span that rounding alone made empty is still tested); the weights'
    // signs decide each pixel. Past the emptiness test, lo and hi lie within the box.
    double lo = x0 + 0.5, hi = x1 + 0.5;
    if (!ClipSpan(wa, py, &lo, &hi) || !ClipSpan(wb, py, &lo, &hi) || !ClipSpan(wc, py, &lo, &hi) ||
        lo > hi + 2.0 * slack)
      continue;
    const int xs = std::max(x0, CeilInt(lo - 0.5 - slack));
    const int xe = std::min(x1, FloorInt(hi - 0.5 + slack));
    for (int x = xs; x <= xe; ++x) {
      const double px = x + 0.5;
      const double ua = wa.At(px, py);
      const double ub = wb.At(px, py);
      const double uc = 1.0 - ua - ub;
      if (ua < 0 || ub < 0 || uc < 0) continue;
      const double depth = ua * a.depth + ub * b.depth + uc * c.depth;
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(g->width) +
                            static_cast<std::size_t>(x);
      if (depth >= static_cast<double>(g->depth[i])) continue;
      g->depth[i] = static_cast<float>(depth);
      g->value[i] =
          static_cast<float>(ua * static_cast<double>(a.value) + ub * static_cast<double>(b.value) +
                             uc * static_cast<double>(c.value));
      Eigen::Vector3f n = static_cast<float>(ua) * a.n + static_cast<float>(ub) * b.n +
                          static_cast<float>(uc) * c.n;
      const float len = n.norm();
      const float lambert = len > 0 ? std::abs(n.dot(light)) / len : 0.0f;
      g->shade[i] = (kAmbient + (1.0f - kAmbient) * lambert) * (back_face ? kBackFaceDim : 1.0f);
      g->id[i] = id;
    }
  }
}

// Image y points down, so an outward-facing (CCW seen from outside) triangle is clockwise here.
bool IsBackFace(const Vertex2& a, const Vertex2& b, const Vertex2& c) {
  return Edge(a, b, c.x, c.y) > 0;
}

// The order to draw a mesh's triangles in, as groups: the front faces of the nearer half of
// the mesh's depth range (by the triangle's first vertex), those of the farther half, then the
// back faces; from the second group on, each is culled by the blocks' farthest depth drawn
// before it (BlockDepthBound), which hides most of the farther half in a side view and most
// back faces. Within a group, tile by tile of the image (16 x 16 pixels, row-major, by the
// first vertex; the mesh's order within a tile), so that consecutive triangles touch pixels
// already in the cache. A pixel's nearest surface does not depend on the order (only exact
// ties in depth would).
struct DrawOrder {
  std::vector<Eigen::Vector3i> triangles;  ///< the mesh's triangles, group after group
  std::vector<std::size_t> group_end;      ///< where each group ends in `triangles`
};

constexpr int kFrontGroups = 2;  ///< depth slices of the front faces (3, 4, 6 measured no faster)

DrawOrder OrderTriangles(const io::TriangleMesh& mesh, const std::vector<Vertex2>& v, int width,
                         int height) {
  constexpr int kTile = 16;
  const int tiles_x = width / kTile + 1;
  const int tiles_y = height / kTile + 1;
  const auto tiles = static_cast<std::size_t>(tiles_x) * static_cast<std::size_t>(tiles_y);
  double dmin = std::numeric_limits<double>::infinity(), dmax = -dmin;
  for (const Vertex2& p : v) {
    dmin = std::min(dmin, p.depth);
    dmax = std::max(dmax, p.depth);
  }
  const double to_group = dmax > dmin ? kFrontGroups / (dmax - dmin) : 0.0;
  const std::size_t groups = (kFrontGroups + 1) * tiles;
  std::vector<std::size_t> key(mesh.num_triangles());
  std::vector<std::size_t> start(groups + 1, 0);
  for (std::size_t t = 0; t < key.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Vertex2& a = v[static_cast<std::size_t>(tri[0])];
    const int tx = std::clamp(static_cast<int>(a.x) / kTile, 0, tiles_x - 1);
    const int ty = std::clamp(static_cast<int>(a.y) / kTile, 0, tiles_y - 1);
    const bool back =
        IsBackFace(a, v[static_cast<std::size_t>(tri[1])], v[static_cast<std::size_t>(tri[2])]);
    const int group =
        back ? kFrontGroups
             : std::clamp(static_cast<int>((a.depth - dmin) * to_group), 0, kFrontGroups - 1);
    key[t] = static_cast<std::size_t>(group) * tiles +
             static_cast<std::size_t>(ty) * static_cast<std::size_t>(tiles_x) +
             static_cast<std::size_t>(tx);
    ++start[key[t] + 1];
  }
  for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
  DrawOrder order;
  for (std::size_t group = 1; group <= kFrontGroups + 1; ++group)
    order.group_end.push_back(start[group * tiles]);
  order.triangles.resize(key.size());
  for (std::size_t t = 0; t < key.size(); ++t) order.triangles[start[key[t]]++] = mesh.triangles[t];
  return order;
}

// The farthest depth drawn in each 8 x 8 block of pixels (infinity while a pixel of it is
// empty): a triangle no nearer than that anywhere in its box would fail every depth test.
// Made before each group of a DrawOrder but the first drawn, it is kept while the group is drawn
// (depths only decrease, so a block's bound only grows stale on the safe side).
class BlockDepthBound {
 public:
  static constexpr int kBlock = 8;

  explicit BlockDepthBound(const GBuffer& g)
      : blocks_x_((g.width + kBlock - 1) / kBlock),
        far_(static_cast<std::size_t>(blocks_x_) *
                 static_cast<std::size_t>((g.height + kBlock - 1) / kBlock),
             -std::numeric_limits<float>::infinity()) {
    // Per block row: each column's farthest depth over the row's pixel rows (element by
    // element, which the compiler vectorizes), then each block's over its columns.
    std::vector<float> column(static_cast<std::size_t>(g.width));
    for (int y0 = 0; y0 < g.height; y0 += kBlock) {
      std::fill(column.begin(), column.end(), -std::numeric_limits<float>::infinity());
      for (int y = y0; y < std::min(g.height, y0 + kBlock); ++y) {
        const float* depth =
            &g.depth[static_cast<std::size_t>(y) * static_cast<std::size_t>(g.width)];
        for (std::size_t x = 0; x < column.size(); ++x)
          column[x] = column[x] < depth[x] ? depth[x] : column[x];
      }
      float* row =
          &far_[static_cast<std::size_t>(y0 / kBlock) * static_cast<std::size_t>(blocks_x_)];
      for (int x = 0; x < g.width; ++x)
        row[x / kBlock] = std::max(row[x / kBlock], column[static_cast<std::size_t>(x)]);
    }
  }

  /// True when every pixel DrawTriangle could test for (a, b, c) holds a surface nearer than
  /// the triangle's nearest vertex (by a margin far above the rounding of interpolated depths).
  bool Hides(const Vertex2& a, const Vertex2& b, const Vertex2& c, int width, int height) const {
    const auto [x0, x1, y0, y1] = BoxOf(a, b, c, width, height);
    if (x0 > x1 || y0 > y1) return true;  // off the image: DrawTriangle tests no pixel
    const double nearest = std::min({a.depth, b.depth, c.depth});
    const double bound = nearest - 1e-6 * (1.0 + std::abs(nearest));
    for (int by = y0 / kBlock; by <= y1 / kBlock; ++by) {
      for (int bx = x0 / kBlock; bx <= x1 / kBlock; ++bx) {
        const float far = far_[static_cast<std::size_t>(by) * static_cast<std::size_t>(blocks_x_) +
                               static_cast<std::size_t>(bx)];
        if (!(static_cast<double>(far) <= bound)) return false;
      }
    }
    return true;
  }

 private:
  int blocks_x_;
  std::vector<float> far_;
};

}  // namespace

Image::Image(int w, int h, Rgb fill)
    : width(w), height(h), rgb(3 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h)) {
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    rgb[i] = fill[0];
    rgb[i + 1] = fill[1];
    rgb[i + 2] = fill[2];
  }
}

OrthoView OrthoView::Scaled(double factor) const {
  OrthoView v = *this;
  v.px_per_mm *= factor;
  v.width = static_cast<int>(std::lround(width * factor));
  v.height = static_cast<int>(std::lround(height * factor));
  v.offset_px = offset_px * factor;
  return v;
}

OrthoView FitView(const Eigen::Vector3d& view_L, const Eigen::Vector3d& up_L,
                  const std::vector<Eigen::Vector3d>& points_L, int width, int height,
                  int margin_px) {
  OrthoView v;
  v.view_L = view_L.normalized();
  v.up_L = (up_L - up_L.dot(v.view_L) * v.view_L).normalized();
  v.right_L = v.up_L.cross(-v.view_L).normalized();
  v.width = width;
  v.height = height;
  Eigen::AlignedBox2d box;
  for (const auto& p : points_L) box.extend(Eigen::Vector2d(p.dot(v.right_L), p.dot(v.up_L)));
  if (box.isEmpty()) return v;
  v.centre_mm = box.center();
  const Eigen::Vector2d size = box.sizes().cwiseMax(1e-3);
  v.px_per_mm =
      std::min((width - 2.0 * margin_px) / size.x(), (height - 2.0 * margin_px) / size.y());
  return v;
}

std::vector<Eigen::Vector3f> VertexNormals(const io::TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d> sum(mesh.num_vertices(), Eigen::Vector3d::Zero());
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d n =
        (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
    for (int k = 0; k < 3; ++k) sum[static_cast<std::size_t>(mesh.triangles[t][k])] += n;
  }
  std::vector<Eigen::Vector3f> out(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    out[i] = sum[i].norm() > 0 ? Eigen::Vector3f(sum[i].normalized().cast<float>())
                               : Eigen::Vector3f::Zero();
  }
  return out;
}

GBuffer Rasterize(const OrthoView& view, const std::vector<Surface>& surfaces) {
  GBuffer g;
  g.width = view.width;
  g.height = view.height;
  const std::size_t n = static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height);
  g.depth.assign(n, std::numeric_limits<float>::infinity());
  g.value.assign(n, 0.0f);
  g.shade.assign(n, 0.0f);
  g.id.assign(n, -1);
  OrthoView local = view;
  local.offset_px = Eigen::Vector2d::Zero();
  // Light from near the viewer, a little from above and the right, for relief.
  const Eigen::Vector3f light =
      (-view.view_L + 0.35 * view.up_L + 0.25 * view.right_L).normalized().cast<float>();
  bool empty = true;  // nothing drawn yet: no bound to cull by
  for (const Surface& s : surfaces) {
    const io::TriangleMesh& mesh = *s.mesh;
    const std::vector<Eigen::Vector3f> normals = VertexNormals(mesh);
    const Eigen::Matrix3f R = s.X_LM.linear().cast<float>();
    std::vector<Vertex2> v(mesh.num_vertices());
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Eigen::Vector3d p_L = s.X_LM * mesh.vertices[i];
      const Eigen::Vector2d px = local.ToPixel(p_L);
      v[i] = {px.x(), px.y(), local.Depth(p_L), s.vertex_values ? (*s.vertex_values)[i] : 0.0f,
              R * normals[i]};
    }
    const DrawOrder order = OrderTriangles(mesh, v, g.width, g.height);
    const auto draw = [&](std::size_t from, std::size_t to, const BlockDepthBound* bound) {
      for (std::size_t k = from; k < to; ++k) {
        const Eigen::Vector3i& tri = order.triangles[k];
        const Vertex2& a = v[static_cast<std::size_t>(tri[0])];
        const Vertex2& b = v[static_cast<std::size_t>(tri[1])];
        const Vertex2& c = v[static_cast<std::size_t>(tri[2])];
        if (bound != nullptr && bound->Hides(a, b, c, g.width, g.height)) continue;
        DrawTriangle(a, b, c, IsBackFace(a, b, c), light, static_cast<std::int16_t>(s.id), &g);
      }
    };
    std::size_t from = 0;
    for (const std::size_t end : order.group_end) {
      if (from == end) continue;
      if (empty) {
        draw(from, end, nullptr);
      } else {
        const BlockDepthBound bound(g);
        draw(from, end, &bound);
      }
      empty = false;
      from = end;
    }
  }
  return g;
}

}  // namespace occlude::app::render
