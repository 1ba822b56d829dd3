// Tooth views (tooth_view.h): cropping the jaw's occlusal view to one tooth, or rasterizing a
// tooth's own triangles, and expressing cells and vertices in tooth coordinates.
#include "tooth_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry_util.h"

namespace occlude::analysis {
namespace {

constexpr double kCentreBandMm = 3.0;  // a crown's centre: its cells this close to its top
constexpr double kMinChordMm = 1.0;    // an arch direction from centres this far apart along u
constexpr double kMaxArchSlope = 0.5;  // at most this turned from the curve (27 deg)

// The middle of the crown's cells within kCentreBandMm of its top, in J (false when it has none).
bool CrownCentre(const ToothView& view, Eigen::Vector3d* centre_J) {
  const HeightMap& map = view.top;
  double top = -std::numeric_limits<double>::infinity();
  for (int c = 0; c < map.nx * map.ny; ++c) {
    if (map.Filled(c)) top = std::max(top, map.height[static_cast<std::size_t>(c)]);
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int c = 0; c < map.nx * map.ny; ++c) {
    if (map.Filled(c) && map.height[static_cast<std::size_t>(c)] >= top - kCentreBandMm) {
      sum += map.Point_J(c);
      ++n;
    }
  }
  if (n == 0) return false;
  *centre_J = sum / n;
  return true;
}

// A map over the bounding box of the cells `keep` of `map`, the others NaN.
HeightMap Crop(const HeightMap& map, const std::vector<int>& keep) {
  HeightMap out;
  out.axes = map.axes;
  out.cell = map.cell;
  if (keep.empty()) return out;
  int i0 = map.nx, i1 = -1, j0 = map.ny, j1 = -1;
  for (const int c : keep) {
    i0 = std::min(i0, c % map.nx), i1 = std::max(i1, c % map.nx);
    j0 = std::min(j0, c / map.nx), j1 = std::max(j1, c / map.nx);
  }
  out.nx = i1 - i0 + 1;
  out.ny = j1 - j0 + 1;
  out.corner = map.corner + map.cell * Eigen::Vector2d(i0, j0);
  out.height.assign(static_cast<std::size_t>(out.nx * out.ny),
                    std::numeric_limits<double>::quiet_NaN());
  out.triangle.assign(out.height.size(), -1);
  for (const int c : keep) {
    const auto k = static_cast<std::size_t>(out.Index(c % map.nx - i0, c / map.nx - j0));
    out.height[k] = map.height[static_cast<std::size_t>(c)];
    out.triangle[k] = map.triangle[static_cast<std::size_t>(c)];
  }
  return out;
}

Eigen::Vector3d Uvw(const ArchCurve::Projection& st, double h, double s_mid, double sign) {
  return {sign * (st.s - s_mid), st.t, h};
}

bool Between(const ToothView& view, const ArchCurve::Projection& st) {
  return st.s >= view.right_cut.At(st.t) && st.s <= view.left_cut.At(st.t);
}

// Fills top_uvw from the cells' projections and the u range of the crown from its cells.
void FillTop(const ArchGeometry& g, ToothView* view) {
  view->top_uvw.assign(view->top.height.size(), Eigen::Vector3d::Zero());
  std::vector<double> u;
  for (int c = 0; c < view->top.nx * view->top.ny; ++c) {
    if (!view->top.Filled(c)) continue;
    const ArchCurve::Projection st = g.curve.Project(view->top.Centre(c));
    view->top_uvw[static_cast<std::size_t>(c)] =
        Uvw(st, view->top.height[static_cast<std::size_t>(c)], view->s_mid, view->mesial_sign);
    u.push_back(view->top_uvw[static_cast<std::size_t>(c)].x());
  }
  if (view->u_mesial == view->u_distal && !u.empty()) {
    view->u_mesial = Quantile(u, 0.99);
    view->u_distal = Quantile(u, 0.01);
  }
}

// The triangles `triangles` of `mesh` (all when empty) whose three vertices the view holds
// (`index`: per mesh vertex its index in the view, -1 when not in it).
void AddTriangles(const io::TriangleMesh& mesh, const std::vector<std::int32_t>& triangles,
                  const std::vector<std::int32_t>& index, ToothView* view) {
  const std::size_t n = triangles.empty() ? mesh.num_triangles() : triangles.size();
  for (std::size_t k = 0; k < n; ++k) {
    const auto t = triangles.empty() ? k : static_cast<std::size_t>(triangles[k]);
    std::array<std::int32_t, 3> tri{};
    bool inside = true;
    for (int c = 0; c < 3; ++c) {
      tri[static_cast<std::size_t>(c)] = index[static_cast<std::size_t>(mesh.triangles[t][c])];
      inside = inside && tri[static_cast<std::size_t>(c)] >= 0;
    }
    if (inside) view->surface_triangles.push_back(tri);
  }
}

}  // namespace

double MesialSign(int fdi) { return (fdi / 10 == 1 || fdi / 10 == 4) ? 1.0 : -1.0; }

double EndU(const ToothView& view, double v, bool mesial) {
  if (view.right_cut.s.empty()) return mesial ? view.u_mesial : view.u_distal;
  // Mesial is towards increasing arc length (the left cut) on the patient's right.
  const ToothCut& cut = (mesial == (view.mesial_sign > 0.0)) ? view.left_cut : view.right_cut;
  return view.mesial_sign * (cut.At(v) - view.s_mid);
}

Eigen::Vector3d ToothCoordinates(const ArchGeometry& g, double s_mid, double mesial_sign,
                                 const Eigen::Vector3d& p_J) {
  return Uvw(g.curve.Project(g.axes.Plane(p_J)), g.axes.Height(p_J), s_mid, mesial_sign);
}

ToothView SegmentedToothView(const io::TriangleMesh& mesh, const ArchGeometry& g, int fdi,
                             io::Jaw jaw, const ToothCut& right, const ToothCut& left,
                             double half_width_mm, double depth_mm) {
  ToothView view;
  view.fdi = fdi;
  view.jaw = jaw;
  view.right_cut = right;
  view.left_cut = left;
  view.s_mid = 0.5 * (right.At(0.0) + left.At(0.0));
  view.mesial_sign = MesialSign(fdi);
  view.u_mesial = 0.5 * (left.At(0.0) - right.At(0.0));
  view.u_distal = -view.u_mesial;
  std::vector<int> cells;
  double top = -std::numeric_limits<double>::infinity();
  for (int c = 0; c < g.top.nx * g.top.ny; ++c) {
    const ArchCurve::Projection& st = g.cell_st[static_cast<std::size_t>(c)];
    if (!g.top.Filled(c) || !Between(view, st) || std::abs(st.t) > half_width_mm) continue;
    cells.push_back(c);
    top = std::max(top, g.top.height[static_cast<std::size_t>(c)]);
  }
  view.top = Crop(g.top, cells);
  FillTop(g, &view);
  std::vector<std::int32_t> index(mesh.num_vertices(), -1);
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const ArchCurve::Projection& st = g.vertex_st[v];
    const double h = g.axes.Height(mesh.vertices[v]);
    if (!Between(view, st) || std::abs(st.t) > half_width_mm || h < top - depth_mm) continue;
    index[v] = static_cast<std::int32_t>(view.surface_J.size());
    view.surface_J.push_back(mesh.vertices[v]);
    view.surface_uvw.push_back(Uvw(st, h, view.s_mid, view.mesial_sign));
  }
  AddTriangles(mesh, {}, index, &view);
  return view;
}

void SetArchSlopes(const ArchGeometry& g, const std::vector<bool>& next_is_neighbour,
                   std::vector<ToothView>* views) {
  const std::size_t n = views->size();
  std::vector<Eigen::Vector3d> centre(n, Eigen::Vector3d::Zero());
  std::vector<bool> has(n, false);
  for (std::size_t k = 0; k < n; ++k) has[k] = CrownCentre((*views)[k], &centre[k]);
  for (std::size_t k = 0; k < n; ++k) {
    ToothView& view = (*views)[k];
    const bool before =
        k > 0 && k - 1 < next_is_neighbour.size() && next_is_neighbour[k - 1] && has[k - 1];
    const bool after =
        k + 1 < n && k < next_is_neighbour.size() && next_is_neighbour[k] && has[k + 1];
    if (!has[k] || (!before && !after)) continue;
    const Eigen::Vector3d a =
        ToothCoordinates(g, view.s_mid, view.mesial_sign, before ? centre[k - 1] : centre[k]);
    const Eigen::Vector3d b =
        ToothCoordinates(g, view.s_mid, view.mesial_sign, after ? centre[k + 1] : centre[k]);
    const Eigen::Vector2d d = (b - a).head<2>();
    if (std::abs(d.x()) < kMinChordMm) continue;
    view.arch_slope = std::clamp(d.y() / d.x(), -kMaxArchSlope, kMaxArchSlope);
  }
}

ToothView ShellToothView(const io::TriangleMesh& mesh, const ArchGeometry& g, int fdi, io::Jaw jaw,
                         const std::vector<std::int32_t>& triangles) {
  ToothView view;
  view.fdi = fdi;
  view.jaw = jaw;
  view.whole_crown = true;
  view.mesial_sign = MesialSign(fdi);
  view.top = RasterizeTop(mesh, triangles, g.axes, g.top.cell);
  std::vector<double> s;
  for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
    if (view.top.Filled(c)) s.push_back(g.curve.Project(view.top.Centre(c)).s);
  }
  view.s_mid = 0.5 * (Quantile(s, 0.01) + Quantile(s, 0.99));
  FillTop(g, &view);
  std::vector<std::int32_t> index(mesh.num_vertices(), -1);
  for (const std::int32_t t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(mesh.triangles[static_cast<std::size_t>(t)][k]);
      if (index[v] >= 0) continue;
      index[v] = static_cast<std::int32_t>(view.surface_J.size());
      view.surface_J.push_back(mesh.vertices[v]);
      view.surface_uvw.push_back(
          Uvw(g.vertex_st[v], g.axes.Height(mesh.vertices[v]), view.s_mid, view.mesial_sign));
    }
  }
  AddTriangles(mesh, triangles, index, &view);
  return view;
}

}  // namespace occlude::analysis
