// The clinical landmarks of the synthetic teeth (clinical.md), placed from the layout and taken
// on the occlusal surface that is really there: each point is a convex combination of the
// corners of the mesh triangle over its (s, t), so it lies on the final mesh (for the upper jaw
// the lower surface lifted by the gap where the design would dip in, not the design), or one of
// its vertices.
//
// Where each lies in the parameter domain: incisal edges at the crown's centre on its edge
// line and cusp tips at the cusp centres, each moved to the crown's locally most prominent mesh
// vertex unless the centre stands out as far (the extreme along the occlusal axis a detector
// finds); the central fossa at the
// centroid of a posterior crown's cusp tips; mesial and distal contact points where neighbouring
// crowns meet (the nominal ends of their spans), across the arch half-way between the two crowns'
// centre lines; facial and lingual mid-crown points on the crown's centre line, where its face has
// come half-way down from the occlusal extreme of that line to the gingiva.
#include <algorithm>
#include <cmath>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

/// The point of the occlusal triangulation over (s, t), clamped to the grid: barycentric weights
/// of the cell's triangle in the parameter domain applied to its corners in L.
Eigen::Vector3d SurfacePoint(const OcclusalGrid& grid,
                             const std::vector<Eigen::Vector3i>& triangles,
                             const std::vector<double>& y, double s, double t) {
  const double a = std::clamp((s - grid.s0) / grid.ds, 0.0, static_cast<double>(grid.ns));
  const double b = std::clamp((t - grid.t0) / grid.dt, 0.0, static_cast<double>(grid.nt));
  const int ci = std::min(static_cast<int>(a), grid.ns - 1);
  const int cj = std::min(static_cast<int>(b), grid.nt - 1);
  Eigen::Vector3d best_point = Eigen::Vector3d::Zero();
  double best_min = -1.0;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3i& tri = triangles[static_cast<std::size_t>(2 * (ci * grid.nt + cj) + k)];
    Eigen::Vector2d corner[3];
    for (int c = 0; c < 3; ++c) {
      corner[c] = Eigen::Vector2d(tri[c] / (grid.nt + 1), tri[c] % (grid.nt + 1));
    }
    const Eigen::Vector2d e1 = corner[1] - corner[0], e2 = corner[2] - corner[0];
    const Eigen::Vector2d q = Eigen::Vector2d(a, b) - corner[0];
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    const double w1 = (q.x() * e2.y() - q.y() * e2.x()) / det;
    const double w2 = (e1.x() * q.y() - e1.y() * q.x()) / det;
    const Eigen::Vector3d w(1.0 - w1 - w2, w1, w2);
    if (w.minCoeff() <= best_min) continue;
    best_min = w.minCoeff();
    best_point.setZero();
    for (int c = 0; c < 3; ++c) {
      const auto v = static_cast<std::size_t>(tri[c]);
      best_point += w[c] * Eigen::Vector3d(grid.xz[v].x(), y[v], grid.xz[v].y());
    }
  }
  return best_point;
}

/// Everything a landmark needs: the grid, its triangles and the jaw's occlusal heights.
struct Surface {
  const OcclusalGrid& grid;
  const std::vector<Eigen::Vector3i>& triangles;
  const std::vector<double>& y;
  const ArchCurve& arch;
  double gingiva_y;
  bool upper;
  const std::vector<int>& vertex_tooth;  ///< crown index per grid vertex (-1 gingiva)
  Eigen::Vector3d At(double s, double t) const { return SurfacePoint(grid, triangles, y, s, t); }
  Eigen::Vector3d Vertex(int v) const {
    const auto k = static_cast<std::size_t>(v);
    return Eigen::Vector3d(grid.xz[k].x(), y[k], grid.xz[k].y());
  }
  /// How far the surface at (s, t) stands out of the gingiva towards the other jaw, mm.
  double Rise(double s, double t) const {
    const double h = At(s, t).y();
    return upper ? gingiva_y - h : h - gingiva_y;
  }
};

/// How far a height stands out towards the other jaw (larger = further).
double Prominence(const Surface& surface, double y) { return surface.upper ? -y : y; }

/// Steps of the tip's climb: at least kTipStepMm and more than a cell, so that a step always
/// reaches the neighbouring vertices.
constexpr double kTipStepMm = 0.8;
constexpr double kTipTieMm = 0.005;  // worn flat tips: a plateau of equal heights
double TipStep(const OcclusalGrid& grid) { return std::max(kTipStepMm, 1.2 * CellDiagonal(grid)); }

/// The vertex of crown `tooth` within a step of the point `at` (grid parameters (s, t)) that
/// stands out furthest towards the other jaw, the nearest among ties; `start` (may be -1) unless
/// one beats it by more than kTipTieMm.
int MostProminentNear(const Surface& surface, int tooth, const Eigen::Vector2d& at, double s,
                      double t, int start) {
  int best = start;
  double best_rise =
      start < 0 ? -1e300
                : Prominence(surface, surface.y[static_cast<std::size_t>(start)]) + kTipTieMm;
  double best_distance = 1e300;
  ForGridVerticesNear(surface.grid, at, s, t, TipStep(surface.grid), [&](int u, double d) {
    const auto n = static_cast<std::size_t>(u);
    if (surface.vertex_tooth[n] != tooth) return;
    const double rise = Prominence(surface, surface.y[n]);
    if (rise > best_rise + kTipTieMm ||
        (rise >= best_rise - kTipTieMm && d < best_distance && (start < 0 || rise > best_rise))) {
      best_rise = std::max(best_rise, rise);
      best_distance = d;
      best = u;
    }
  });
  return best;
}

/// The tip of a cusp or incisal edge designed at (s, t) on crown `tooth`, as the final surface
/// has it: the crown's most prominent grid vertex within a step of the design, then steepest
/// ascent towards the other jaw over the crown's vertices (at most kTipClimbs steps). The design
/// point itself when it stands out as far (a flat worn tip), else the vertex reached.
Eigen::Vector3d Tip(const Surface& surface, int tooth, double s, double t) {
  constexpr int kTipClimbs = 4;
  const OcclusalGrid& grid = surface.grid;
  const Eigen::Vector2d at = ArchPoint(surface.arch, s) + t * ArchNormal(surface.arch, s);
  int v = MostProminentNear(surface, tooth, at, s, t, -1);
  Eigen::Vector3d design = surface.At(s, t);
  if (v < 0) return design;  // no vertex of the crown nearby (not on valid grids)
  for (int step = 0; step < kTipClimbs; ++step) {
    const auto k = static_cast<std::size_t>(v);
    const int next = MostProminentNear(surface, tooth, grid.xz[k], grid.S(v / (grid.nt + 1)),
                                       grid.T(v % (grid.nt + 1)), v);
    if (next == v) break;
    v = next;
  }
  const Eigen::Vector3d climbed = surface.Vertex(v);
  const bool flat = Prominence(surface, design.y()) >= Prominence(surface, climbed.y()) - kTipTieMm;
  return flat ? design : climbed;
}

/// The mid-crown point of one face: on the line s = tooth.s_center from the crown's outline on
/// that side (outward = +1 facial, -1 lingual) inwards, where the rise reaches half the line's
/// largest rise (scan at a quarter cell, then bisection).
Eigen::Vector3d MidCrown(const Surface& surface, const Tooth& tooth, int outward) {
  const double s = tooth.s_center;
  const double outline = tooth.t_center + outward * tooth.half_width;
  const double step = 0.25 * surface.grid.dt;
  const int steps = static_cast<int>(std::ceil(2.0 * tooth.half_width / step));
  double top = 0.0;
  for (int k = 0; k <= steps; ++k)
    top = std::max(top, surface.Rise(s, outline - outward * k * step));
  double out = outline, in = outline;  // Rise(out) < half <= Rise(in)
  for (int k = 1; k <= steps; ++k) {
    in = outline - outward * k * step;
    if (surface.Rise(s, in) >= 0.5 * top) break;
    out = in;
  }
  for (int k = 0; k < 40; ++k) {
    const double mid = 0.5 * (out + in);
    (surface.Rise(s, mid) >= 0.5 * top ? in : out) = mid;
  }
  return surface.At(s, in);
}

Eigen::Vector2d FossaAt(const Tooth& tooth) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Cusp& cusp : tooth.cusps) sum += Eigen::Vector2d(cusp.s, cusp.t);
  return sum / static_cast<double>(tooth.cusps.size());
}

/// The neighbour of teeth[k] on its mesial (towards = -1) or distal (+1) side, if any.
const Tooth* Neighbour(const std::vector<Tooth>& teeth, std::size_t k, int towards) {
  // teeth are sorted by s: distal is away from the midline, so +side along the list.
  const long step = towards * teeth[k].side;
  const long n = static_cast<long>(k) + step;
  if (n < 0 || n >= static_cast<long>(teeth.size())) return nullptr;
  return &teeth[static_cast<std::size_t>(n)];
}

void AddToothLandmarks(const Surface& surface, const std::vector<Tooth>& teeth, std::size_t k,
                       Jaw jaw, std::vector<Landmark>* out) {
  const Tooth& tooth = teeth[k];
  const int fdi = FdiFromUniversal(tooth.number);
  const auto add = [&](LandmarkType type, const Eigen::Vector3d& p) {
    out->push_back(Landmark{jaw, fdi, type, p});
  };
  const bool incisor = tooth.tooth_class <= kLateralIncisor;
  const int index = static_cast<int>(k);
  if (incisor) {
    const double t_edge = tooth.t_center + tooth.edge_v * tooth.half_width;
    add(LandmarkType::kIncisalEdge, Tip(surface, index, tooth.s_center, t_edge));
  }
  for (const Cusp& cusp : tooth.cusps) add(cusp.type, Tip(surface, index, cusp.s, cusp.t));
  if (tooth.tooth_class >= kFirstPremolar) {
    const Eigen::Vector2d fossa = FossaAt(tooth);
    add(LandmarkType::kCentralFossa, surface.At(fossa.x(), fossa.y()));
  }
  for (const int towards : {-1, 1}) {
    const Tooth* other = Neighbour(teeth, k, towards);
    const double t = other ? 0.5 * (tooth.t_center + other->t_center) : tooth.t_center;
    const double s = towards < 0 ? tooth.s_mesial : tooth.s_distal;
    add(towards < 0 ? LandmarkType::kMesial : LandmarkType::kDistal, surface.At(s, t));
  }
  add(LandmarkType::kFacial, MidCrown(surface, tooth, 1));
  add(LandmarkType::kLingual, MidCrown(surface, tooth, -1));
}

}  // namespace

std::vector<Landmark> JawLandmarks(const JawLayout& jaw, bool upper, const ArchCurve& arch,
                                   const OcclusalGrid& grid,
                                   const std::vector<Eigen::Vector3i>& triangles,
                                   const std::vector<double>& occlusal_y,
                                   const std::vector<int>& vertex_tooth) {
  const Surface surface{grid, triangles, occlusal_y, arch, jaw.gingiva_y, upper, vertex_tooth};
  std::vector<Landmark> landmarks;
  for (std::size_t k = 0; k < jaw.teeth.size(); ++k) {
    AddToothLandmarks(surface, jaw.teeth, k, upper ? Jaw::kUpper : Jaw::kLower, &landmarks);
  }
  std::stable_sort(landmarks.begin(), landmarks.end(),
                   [](const Landmark& a, const Landmark& b) { return a.tooth_fdi < b.tooth_fdi; });
  return landmarks;
}

}  // namespace occlude::io::synthetic
