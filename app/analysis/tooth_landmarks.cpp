// Landmark rules per tooth class (tooth_landmarks.h). Regions are in tooth coordinates relative
// to the crown's middle: u_rel = (u - u_mid) / length in [-1/2, 1/2] (mesial positive) and the
// side of v against the crown's middle across the arch.
#include "tooth_landmarks.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "geometry_util.h"
#include "occlusal_plane.h"

namespace occlude::analysis {
namespace {

using io::LandmarkType;

constexpr double kCuspRadiusMm = 1.0;  // a cusp tip is the highest point this far around
constexpr double kCuspProminenceMm = 0.05;
constexpr double kPlateauMm = 0.05;       // a cusp's plateau: cells this close to its peak's height
constexpr double kFallbackSliceMm = 0.4;  // a cusp region without a peak: its middle slice
constexpr double kCutCells = 2.0;  // a peak this close to a segmented view's cut: the cut slope
constexpr double kTableMm = 2.5;   // the occlusal table: the crown's cells this close to its top
constexpr double kMaxTableSlope = 0.35;     // its plane inclined at most this (19 deg)
constexpr double kIncisalSliceShare = 0.1;  // incisal edge: middle tenth of the crown's length
constexpr double kIncisalRidgeMm = 0.15;    // ... its cells this close to the slice's top
// A canine's tip lies mesial of its crown's middle (its mesial cusp ridge is the shorter one,
// Wheeler): u_rel in [kCanineDistalShare, kCanineMesialShare]. Its top there is a worn dome
// whose highest cells wander along the flat crest; seen along the occlusal axis, though, the
// two cusp ridges run back lingually from the tip, so the crown's labial outline near its top
// bulges most at the tip (the top of the labial ridge). Along the arch the tip is where the
// region's cells within kCanineCapMm of its top reach farthest labially (the middle of the
// kCanineBinMm slices whose outermost cell is within kCanineOutlineTolMm of the outermost), and
// across at the middle of the cells of that slice (kCanineSliceMm either side) within
// kCanineRidgeMm of the slice's top.
constexpr double kCanineDistalShare = -0.1, kCanineMesialShare = 0.3;
constexpr double kCanineCapMm = 0.5;
constexpr double kCanineBinMm = 0.4;
constexpr double kCanineOutlineTolMm = 0.2;
constexpr double kCanineSliceMm = 0.4;
constexpr double kCanineRidgeMm = 0.15;
constexpr double kCanineEdgeCells = 2.0;      // a region top this close to its end: less sure
constexpr double kFossaShare = 0.2;           // central fossa: middle fifth both ways ...
constexpr double kFossaFloorMm = 0.3;         // ... the middle of its cells this near its lowest
constexpr double kContactBandMm = 0.5;        // contact points: this close to the crown's end
constexpr double kContactDepthMm = 5.0;       // ... and at most this below its top
constexpr double kContactAcrossShare = 0.35;  // ... and this close to its middle across
constexpr double kContactSearchMm = 2.5;      // whole crowns: the closest pair this near ends
constexpr double kContactTieMm = 0.05;        // ... or the highest of pairs this much farther
constexpr double kClinicalCrownShare = 0.8;
constexpr double kCrownBandMm = 3.0;  // a crown's extent across: its cells this close to its top //
                                      // the gingiva covers the rest of the crown

// Wheeler's anatomical crown heights (cervical line to cusp tip / incisal edge), positions 1-8.
constexpr double kUpperCrownMm[8] = {10.5, 9.0, 10.0, 8.5, 7.5, 7.5, 7.0, 6.5};
constexpr double kLowerCrownMm[8] = {9.0, 9.5, 11.0, 8.5, 8.0, 7.5, 7.0, 6.5};

enum class Side { kAny, kBuccal, kLingual };

// A cusp's region: u_rel within [u_lo, u_hi], on `side` of the middle across.
struct CuspSlot {
  LandmarkType type;
  double u_lo, u_hi;
  Side side;
};

// A lower first molar's three buccal cusps: the mesiobuccal in the mesial third (u_rel above
// kLowerMolarBuccalGroove), the distal (`db_cusp`), the smallest, in the distal quarter (below
// kLowerMolarDistobuccalGroove; Wheeler: about a quarter of the crown's length), the distobuccal
// (`middle_buccal_cusp`) between.
constexpr double kLowerMolarBuccalGroove = 1.0 / 6.0, kLowerMolarDistobuccalGroove = -0.25;

std::vector<CuspSlot> CuspSlots(io::Jaw jaw, int position) {
  const bool upper = jaw == io::Jaw::kUpper;
  if (position == 4 || (position == 5 && upper)) {
    return {{LandmarkType::kBuccalCusp, -0.5, 0.5, Side::kBuccal},
            {LandmarkType::kLingualCusp, -0.5, 0.5, Side::kLingual}};
  }
  if (position == 5) {  // lower second premolar: one buccal, two lingual cusps
    return {{LandmarkType::kBuccalCusp, -0.5, 0.5, Side::kBuccal},
            {LandmarkType::kMlCusp, 0.0, 0.5, Side::kLingual},
            {LandmarkType::kDlCusp, -0.5, 0.0, Side::kLingual}};
  }
  std::vector<CuspSlot> slots = {{LandmarkType::kMlCusp, 0.0, 0.5, Side::kLingual},
                                 {LandmarkType::kDlCusp, -0.5, 0.0, Side::kLingual}};
  if (!upper && position == 6) {  // lower first molar: three buccal cusps
    slots.push_back({LandmarkType::kMbCusp, kLowerMolarBuccalGroove, 0.5, Side::kBuccal});
    slots.push_back({LandmarkType::kMiddleBuccalCusp, kLowerMolarDistobuccalGroove,
                     kLowerMolarBuccalGroove, Side::kBuccal});
    slots.push_back({LandmarkType::kDbCusp, -0.5, kLowerMolarDistobuccalGroove, Side::kBuccal});
  } else {
    slots.push_back({LandmarkType::kMbCusp, 0.0, 0.5, Side::kBuccal});
    slots.push_back({LandmarkType::kDbCusp, -0.5, 0.0, Side::kBuccal});
  }
  return slots;
}

// The crown's middle and size in tooth coordinates.
struct CrownBox {
  double u_mid = 0.0, length = 1.0, v_mid = 0.0, width = 1.0, top = 0.0;
};

CrownBox Box(const ToothView& view) {
  CrownBox box;
  box.top = -std::numeric_limits<double>::infinity();
  for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
    if (view.top.Filled(c))
      box.top = std::max(box.top, view.top_uvw[static_cast<std::size_t>(c)].z());
  }
  // Across the arch, the crown alone: the cells within kCrownBandMm of its top (a scan's view
  // also holds gingiva and, on an upper jaw, palate within its reach of the curve).
  std::vector<double> v;
  for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
    const Eigen::Vector3d& x = view.top_uvw[static_cast<std::size_t>(c)];
    if (view.top.Filled(c) && x.z() >= box.top - kCrownBandMm) v.push_back(x.y());
  }
  box.u_mid = 0.5 * (view.u_mesial + view.u_distal);
  box.length = std::max(view.u_mesial - view.u_distal, 1e-6);
  box.v_mid = 0.5 * (Quantile(v, 0.05) + Quantile(v, 0.95));
  box.width = std::max(Quantile(v, 0.95) - Quantile(v, 0.05), 1e-6);
  return box;
}

bool OnSide(Side side, double v, const CrownBox& box) {
  return side == Side::kAny || (side == Side::kBuccal ? v > box.v_mid : v < box.v_mid);
}

ArchLandmark Make(const ToothView& view, LandmarkType type, const Eigen::Vector3d& p_J,
                  double confidence, const char* method) {
  ArchLandmark l;
  l.landmark.jaw = view.jaw;
  l.landmark.tooth_fdi = view.fdi;
  l.landmark.type = type;
  l.landmark.p = p_J;
  l.confidence = std::clamp(confidence, 0.0, 1.0);
  l.method = method;
  return l;
}

// The cusps clinical.md's relationships use: canine tips, buccal cusps of premolars, the
// mesiobuccal and middle buccal cusps of molars.
bool MeasuredCusp(LandmarkType type) {
  return type == LandmarkType::kCuspTip || type == LandmarkType::kBuccalCusp ||
         type == LandmarkType::kMbCusp || type == LandmarkType::kMiddleBuccalCusp;
}

// The middle of the plateau around a peak cell: the mean of the cells within kCuspRadiusMm
// whose height is within kPlateauMm of the peak's (a flat top has no single highest cell).
Eigen::Vector3d PlateauCentre(const HeightMap& map, int peak) {
  const double h = map.height[static_cast<std::size_t>(peak)];
  const Eigen::Vector2d q = map.Centre(peak);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int c = 0; c < map.nx * map.ny; ++c) {
    if (!map.Filled(c) || map.height[static_cast<std::size_t>(c)] < h - kPlateauMm ||
        (map.Centre(c) - q).norm() > kCuspRadiusMm)
      continue;
    sum += map.Point_J(c);
    ++n;
  }
  return sum / n;
}

// The local maxima of the crown's view (HeightPeaks over kCuspRadiusMm). A segmented view is cut
// out of the jaw's at the boundaries with its neighbours, so a slope rising on into the
// neighbour (its marginal ridge, its cusp ridge) tops out at the cut: the peaks within
// kCutCells cells of a cut end are left out (a cusp near a cut that falls off before it stays).
std::vector<int> CrownPeaks(const ToothView& view) {
  const double margin = kCutCells * view.top.cell;
  std::vector<int> peaks;
  for (const int c : HeightPeaks(view.top, kCuspRadiusMm, kCuspProminenceMm)) {
    const Eigen::Vector3d& x = view.top_uvw[static_cast<std::size_t>(c)];
    const bool at_cut =
        EndU(view, x.y(), true) - x.x() < margin || x.x() - EndU(view, x.y(), false) < margin;
    if (view.whole_crown || !at_cut) peaks.push_back(c);
  }
  return peaks;
}

// Cusp tips: in each slot's region the highest peak, more sure when it is the region's top.
void AddCusps(const ToothView& view, const CrownBox& box, std::vector<ArchLandmark>* out) {
  const std::vector<int> peaks = CrownPeaks(view);
  for (const CuspSlot& slot : CuspSlots(view.jaw, io::ToothPosition(view.fdi))) {
    int best = -1;
    double region_top = -std::numeric_limits<double>::infinity();
    const auto inside = [&](int c) {
      const Eigen::Vector3d& x = view.top_uvw[static_cast<std::size_t>(c)];
      const double u = (x.x() - box.u_mid) / box.length;
      return u >= slot.u_lo && u <= slot.u_hi && OnSide(slot.side, x.y(), box);
    };
    for (const int c : peaks) {
      if (inside(c) && (best < 0 || view.top.height[static_cast<std::size_t>(c)] >
                                        view.top.height[static_cast<std::size_t>(best)])) {
        best = c;
      }
    }
    int top_cell = -1;
    for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
      if (view.top.Filled(c) && inside(c) &&
          view.top.height[static_cast<std::size_t>(c)] > region_top) {
        region_top = view.top.height[static_cast<std::size_t>(c)];
        top_cell = c;
      }
    }
    // A region without a local maximum (a worn or merged cusp, a cusp ridge sloping on through
    // it): for the cusps a relationship rests on (molar, crossbite), less sure, the highest cell
    // of its middle slice (kFallbackSliceMm either side of the slot's middle along the arch;
    // the region's highest cell lies at its end, where the slope runs on into the next cusp);
    // the others are left out.
    if (best < 0 && top_cell >= 0 && MeasuredCusp(slot.type)) {
      const double u_middle = box.u_mid + 0.5 * (slot.u_lo + slot.u_hi) * box.length;
      int middle_top = -1;
      for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
        const double u = view.top_uvw[static_cast<std::size_t>(c)].x();
        if (!view.top.Filled(c) || !inside(c) || std::abs(u - u_middle) > kFallbackSliceMm)
          continue;
        if (middle_top < 0 || view.top.height[static_cast<std::size_t>(c)] >
                                  view.top.height[static_cast<std::size_t>(middle_top)])
          middle_top = c;
      }
      out->push_back(Make(view, slot.type,
                          view.top.Point_J(middle_top >= 0 ? middle_top : top_cell), 0.4,
                          "highest point of the cusp region's middle (no local maximum in it)"));
      continue;
    }
    if (best < 0) continue;
    const bool is_top = view.top.height[static_cast<std::size_t>(best)] >= region_top - 1e-9;
    out->push_back(Make(view, slot.type, PlateauCentre(view.top, best), is_top ? 0.9 : 0.6,
                        "highest local maximum of the occlusal surface in the cusp's region"));
  }
}

// Cusps found on the crown's heights above the plane fitted through its occlusal table (its
// cells within kTableMm of its top), its slope limited to kMaxTableSlope: a crown inclined by the
// curves of Wilson and Spee (upper molars' buccal cusps 1-2 mm above their palatal ones) has its
// cusp tips on a slope of the occlusal view, where the view's local maxima lie off them or are
// missing. The points keep their heights.
void AddTiltedCusps(const ToothView& view, const CrownBox& box, std::vector<ArchLandmark>* out) {
  const HeightMap& map = view.top;
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (int c = 0; c < map.nx * map.ny; ++c) {
    if (!map.Filled(c) || map.height[static_cast<std::size_t>(c)] < box.top - kTableMm) continue;
    const Eigen::Vector3d a(1.0, map.Centre(c).x(), map.Centre(c).y());
    normal += a * a.transpose();
    rhs += a * map.height[static_cast<std::size_t>(c)];
  }
  Eigen::Vector3d k = normal.ldlt().solve(rhs);
  if (!k.allFinite()) return AddCusps(view, box, out);
  const double slope = k.tail<2>().norm();
  if (slope > kMaxTableSlope) k.tail<2>() *= kMaxTableSlope / slope;
  const auto trend = [&](const Eigen::Vector2d& q) { return k(1) * q.x() + k(2) * q.y(); };
  ToothView level = view;
  for (int c = 0; c < map.nx * map.ny; ++c) {
    if (map.Filled(c)) level.top.height[static_cast<std::size_t>(c)] -= trend(map.Centre(c));
  }
  const std::size_t first = out->size();
  AddCusps(level, box, out);
  for (std::size_t i = first; i < out->size(); ++i) {
    Eigen::Vector3d& p = (*out)[i].landmark.p;
    p += trend(map.axes.Plane(p)) * map.axes.up_J;
  }
}

// The filled cells of `map` that `keep` accepts within tol_mm of the highest of them (empty when
// `keep` accepts none); *top_cell (if given) that highest, the first of equals (-1 when none).
template <typename Keep>
std::vector<int> CellsNearTop(const HeightMap& map, double tol_mm, Keep keep,
                              int* top_cell = nullptr) {
  const auto h_of = [&](int c) { return map.height[static_cast<std::size_t>(c)]; };
  const int cells = map.nx * map.ny;
  int top = -1;
  for (int c = 0; c < cells; ++c) {
    if (map.Filled(c) && keep(c) && (top < 0 || h_of(c) > h_of(top))) top = c;
  }
  if (top_cell) *top_cell = top;
  std::vector<int> near;
  if (top < 0) return near;
  for (int c = 0; c < cells; ++c) {
    if (map.Filled(c) && keep(c) && h_of(c) >= h_of(top) - tol_mm) near.push_back(c);
  }
  return near;
}

// The middle u of the kCanineBinMm slices of `cells` (non-empty) whose outermost cell (largest
// v) lies within kCanineOutlineTolMm of the outermost of all.
double LabialmostSlice(const ToothView& view, const std::vector<int>& cells) {
  std::map<long, double> outer;  // slice index -> largest v
  for (const int c : cells) {
    const Eigen::Vector3d& x = view.top_uvw[static_cast<std::size_t>(c)];
    const long k = std::lround(x.x() / kCanineBinMm);
    const auto it = outer.find(k);
    if (it == outer.end() || x.y() > it->second) outer[k] = x.y();
  }
  double most = -std::numeric_limits<double>::infinity();
  for (const auto& [k, v] : outer) most = std::max(most, v);
  double sum = 0.0;
  int n = 0;
  for (const auto& [k, v] : outer) {
    if (v >= most - kCanineOutlineTolMm) sum += kCanineBinMm * static_cast<double>(k), ++n;
  }
  return sum / n;
}

// The canine's tip (kCanineCapMm above): the labialmost slice of its region's top along the
// arch, then the middle of that slice's highest cells across it, as the surface point seen there.
// Less sure when the region's top lies at its end (the crest rises on out of the region).
void AddCanineTip(const ToothView& view, const CrownBox& box, std::vector<ArchLandmark>* out) {
  const HeightMap& map = view.top;
  const auto u_of = [&](int c) { return view.top_uvw[static_cast<std::size_t>(c)].x(); };
  const double u_lo = box.u_mid + kCanineDistalShare * box.length;
  const double u_hi = box.u_mid + kCanineMesialShare * box.length;
  int top_cell = -1;
  const std::vector<int> cap = CellsNearTop(
      map, kCanineCapMm, [&](int c) { return u_of(c) >= u_lo && u_of(c) <= u_hi; }, &top_cell);
  if (cap.empty()) return;
  const double u_tip = LabialmostSlice(view, cap);
  int slice_top = -1;
  const std::vector<int> ridge = CellsNearTop(
      map, kCanineRidgeMm, [&](int c) { return std::abs(u_of(c) - u_tip) <= kCanineSliceMm; },
      &slice_top);
  if (ridge.empty()) return;
  Eigen::Vector2d q = Eigen::Vector2d::Zero();
  for (const int c : ridge) q += map.Centre(c);
  const int at = map.CellAt(q / static_cast<double>(ridge.size()));
  const int tip = at >= 0 && map.Filled(at) ? at : slice_top;
  const double edge = kCanineEdgeCells * map.cell;
  const bool at_end = u_of(top_cell) - u_lo < edge || u_hi - u_of(top_cell) < edge;
  out->push_back(Make(view, LandmarkType::kCuspTip, map.Point_J(tip), at_end ? 0.5 : 0.8,
                      "middle of the highest cells of the canine's tip region"));
}

// The incisal edge's middle: the mean of the cells of the crown's middle slice (kIncisalSliceShare
// of its length either side of the middle of its span) within kIncisalRidgeMm of the slice's
// highest (a flat edge has no single highest point). The middle of the span, not of the ridge's
// highest cells: an edge sloping towards one corner (worn, tipped) has them at that end.
void AddIncisalEdge(const ToothView& view, const CrownBox& box, std::vector<ArchLandmark>* out) {
  const auto u_of = [&](int c) { return view.top_uvw[static_cast<std::size_t>(c)].x(); };
  const double half = std::max(kIncisalSliceShare * box.length, view.top.cell);
  const std::vector<int> edge = CellsNearTop(
      view.top, kIncisalRidgeMm, [&](int c) { return std::abs(u_of(c) - box.u_mid) <= half; });
  if (edge.empty()) return;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const int c : edge) sum += view.top.Point_J(c);
  out->push_back(Make(view, LandmarkType::kIncisalEdge, sum / static_cast<double>(edge.size()), 0.8,
                      "middle of the highest cells of the incisal edge's middle slice"));
}

// The central fossa: the middle of the lowest cells of the crown's middle (within kFossaFloorMm
// of the lowest: a worn or flat floor has no single lowest point).
void AddCentralFossa(const ToothView& view, const CrownBox& box, std::vector<ArchLandmark>* out) {
  int best = -1;
  const auto in_middle = [&](int c) {
    const Eigen::Vector3d& x = view.top_uvw[static_cast<std::size_t>(c)];
    return view.top.Filled(c) && std::abs(x.x() - box.u_mid) <= kFossaShare * box.length &&
           std::abs(x.y() - box.v_mid) <= kFossaShare * box.width;
  };
  for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
    if (!in_middle(c)) continue;
    if (best < 0 || view.top.height[static_cast<std::size_t>(c)] <
                        view.top.height[static_cast<std::size_t>(best)])
      best = c;
  }
  if (best < 0) return;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int n = 0;
  for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
    if (in_middle(c) && view.top.height[static_cast<std::size_t>(c)] <=
                            view.top.height[static_cast<std::size_t>(best)] + kFossaFloorMm)
      sum += view.top.Centre(c), ++n;
  }
  const int at = view.top.CellAt(sum / n);
  const int cell = at >= 0 && view.top.Filled(at) ? at : best;
  out->push_back(Make(view, LandmarkType::kCentralFossa, view.top.Point_J(cell), 0.6,
                      "middle of the lowest points of the occlusal surface's middle"));
}

// Contact points: a whole crown's most mesial / distal surface point near its top; on a scan,
// the highest point at the boundary with the neighbour (the bottom of the occlusal embrasure).
void AddContacts(const ToothView& view, const CrownBox& box, std::vector<ArchLandmark>* out) {
  for (const bool mesial : {true, false}) {
    const double sign = mesial ? 1.0 : -1.0;
    const LandmarkType type = mesial ? LandmarkType::kMesial : LandmarkType::kDistal;
    const double across = kContactAcrossShare * box.width;
    if (view.whole_crown) {
      int best = -1;
      for (std::size_t i = 0; i < view.surface_uvw.size(); ++i) {
        const Eigen::Vector3d& x = view.surface_uvw[i];
        if (x.z() < box.top - kContactDepthMm || std::abs(x.y() - box.v_mid) > across) continue;
        if (best < 0 || sign * x.x() > sign * view.surface_uvw[static_cast<std::size_t>(best)].x())
          best = static_cast<int>(i);
      }
      if (best >= 0) {
        out->push_back(Make(view, type, view.surface_J[static_cast<std::size_t>(best)], 0.8,
                            "most mesial / distal point of the crown near its top"));
      }
      continue;
    }
    int best = -1;
    for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
      if (!view.top.Filled(c)) continue;
      const Eigen::Vector3d& x = view.top_uvw[static_cast<std::size_t>(c)];
      if (sign * (EndU(view, x.y(), mesial) - x.x()) > kContactBandMm ||
          std::abs(x.y() - box.v_mid) > across)
        continue;
      if (best < 0 || view.top.height[static_cast<std::size_t>(c)] >
                          view.top.height[static_cast<std::size_t>(best)])
        best = c;
    }
    if (best >= 0) {
      out->push_back(Make(view, type, view.top.Point_J(best), 0.6,
                          "highest point at the boundary with the neighbouring crown"));
    }
  }
}

// The outermost point (sign +1: largest v, -1: smallest) on the `sign` side of v_mid where the
// line u = u0, w = w0 across the arch meets the view's surface triangles (in tooth coordinates,
// the point itself interpolated in J); false when it meets none there.
bool OutermostOnLine(const ToothView& view, double u0, double w0, double sign, double v_mid,
                     Eigen::Vector3d* p_J) {
  double best = -std::numeric_limits<double>::infinity();
  for (const auto& tri : view.surface_triangles) {
    const Eigen::Vector3d& a = view.surface_uvw[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector3d& b = view.surface_uvw[static_cast<std::size_t>(tri[1])];
    const Eigen::Vector3d& c = view.surface_uvw[static_cast<std::size_t>(tri[2])];
    // Barycentric coordinates of (u0, w0) in the triangle projected on the (u, w) plane.
    const double det = (b.x() - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (b.z() - a.z());
    if (std::abs(det) < 1e-12) continue;
    const double l1 = ((u0 - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (w0 - a.z())) / det;
    const double l2 = ((b.x() - a.x()) * (w0 - a.z()) - (u0 - a.x()) * (b.z() - a.z())) / det;
    const double l0 = 1.0 - l1 - l2;
    if (l0 < 0.0 || l1 < 0.0 || l2 < 0.0) continue;
    const double v = l0 * a.y() + l1 * b.y() + l2 * c.y();
    if (sign * (v - v_mid) <= 0.0 || sign * v <= best) continue;
    best = sign * v;
    *p_J = l0 * view.surface_J[static_cast<std::size_t>(tri[0])] +
           l1 * view.surface_J[static_cast<std::size_t>(tri[1])] +
           l2 * view.surface_J[static_cast<std::size_t>(tri[2])];
  }
  return std::isfinite(best);
}

// The highest cell of the crown on the `sign` side of its middle across (+1 facial, -1
// lingual); the crown's top when that side has none.
double SideTop(const ToothView& view, const CrownBox& box, double sign) {
  double top = -std::numeric_limits<double>::infinity();
  for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
    const Eigen::Vector3d& x = view.top_uvw[static_cast<std::size_t>(c)];
    if (view.top.Filled(c) && sign * (x.y() - box.v_mid) > 0.0) top = std::max(top, x.z());
  }
  return std::isfinite(top) ? top : box.top;
}

// Facial / lingual: the outermost surface point on each side, half the clinical crown's height
// below that side's top (its own cusps or edge: molars tilt buccally in the upper jaw and
// lingually in the lower, so one side's cusps stand 1-2 mm above the other's), in the crown's
// middle along the arch there (between its cuts at that side's outline: a rotated crown's
// middle moves along the arch from its lingual to its facial side), on the line across turned
// square to the row of teeth (view.arch_slope), not to the curve.
void AddSurfacePoints(const ToothView& view, const CrownBox& box, std::vector<ArchLandmark>* out) {
  const double depth =
      0.5 * kClinicalCrownShare * TypicalCrownHeightMm(view.jaw, io::ToothPosition(view.fdi));
  for (const bool facial : {true, false}) {
    const double sign = facial ? 1.0 : -1.0;
    const double target = SideTop(view, box, sign) - depth;
    const double v_side = box.v_mid + sign * 0.5 * box.width;
    const double u_side = 0.5 * (EndU(view, v_side, true) + EndU(view, v_side, false));
    const double u0 = u_side - (v_side - box.v_mid) * view.arch_slope;
    Eigen::Vector3d p_J = Eigen::Vector3d::Zero();
    // The turned line may pass the end of a short crown's side: then square to the curve.
    if (OutermostOnLine(view, u0, target, sign, box.v_mid, &p_J) ||
        OutermostOnLine(view, u_side, target, sign, box.v_mid, &p_J)) {
      out->push_back(Make(view, facial ? LandmarkType::kFacial : LandmarkType::kLingual, p_J, 0.5,
                          "outer surface of the crown's middle, half the clinical crown down"));
    }
  }
}

// The vertices of a whole crown near its end facing the neighbour (mesial or distal), within
// kContactDepthMm of its top and kContactAcrossShare of its width from its middle across.
std::vector<std::size_t> NearEnd(const ToothView& view, bool mesial) {
  const CrownBox box = Box(view);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < view.surface_uvw.size(); ++i) {
    const Eigen::Vector3d& x = view.surface_uvw[i];
    const double inside = mesial ? view.u_mesial - x.x() : x.x() - view.u_distal;
    if (inside <= kContactSearchMm && x.z() >= box.top - kContactDepthMm &&
        std::abs(x.y() - box.v_mid) <= kContactAcrossShare * box.width)
      out.push_back(i);
  }
  return out;
}

void ReplaceLandmark(ArchLandmark l, std::vector<ArchLandmark>* landmarks) {
  for (ArchLandmark& d : *landmarks) {
    if (d.landmark.jaw == l.landmark.jaw && d.landmark.tooth_fdi == l.landmark.tooth_fdi &&
        d.landmark.type == l.landmark.type) {
      d = std::move(l);
      return;
    }
  }
  landmarks->push_back(std::move(l));
}

}  // namespace

void PlaceContacts(const ToothView& a, const ToothView& b, double tooth_confidence,
                   std::vector<ArchLandmark>* landmarks) {
  if (!a.whole_crown || !b.whole_crown) return;
  // Along the arch right to left: a faces b with its mesial end on the right side, b faces a
  // with its mesial end on the left side.
  const bool a_mesial = !io::IsLeftSide(a.fdi), b_mesial = io::IsLeftSide(b.fdi);
  const std::vector<std::size_t> ia = NearEnd(a, a_mesial), ib = NearEnd(b, b_mesial);
  if (ia.empty() || ib.empty()) return;
  // The closest pair; among pairs as close within kContactTieMm (crowns sharing a face) the
  // highest.
  double closest = std::numeric_limits<double>::infinity();
  for (const std::size_t i : ia) {
    for (const std::size_t j : ib) {
      closest = std::min(closest, (a.surface_J[i] - b.surface_J[j]).norm());
    }
  }
  double best_height = -std::numeric_limits<double>::infinity();
  std::size_t best_a = 0, best_b = 0;
  for (const std::size_t i : ia) {
    for (const std::size_t j : ib) {
      const double h = a.surface_uvw[i].z() + b.surface_uvw[j].z();
      if ((a.surface_J[i] - b.surface_J[j]).norm() <= closest + kContactTieMm && h > best_height)
        best_height = h, best_a = i, best_b = j;
    }
  }
  const char* method = "closest point to the neighbouring crown";
  ReplaceLandmark(Make(a, a_mesial ? LandmarkType::kMesial : LandmarkType::kDistal,
                       a.surface_J[best_a], 0.9 * tooth_confidence, method),
                  landmarks);
  ReplaceLandmark(Make(b, b_mesial ? LandmarkType::kMesial : LandmarkType::kDistal,
                       b.surface_J[best_b], 0.9 * tooth_confidence, method),
                  landmarks);
}

double TypicalCrownHeightMm(io::Jaw jaw, int position) {
  const int i = std::clamp(position, 1, 8) - 1;
  return jaw == io::Jaw::kUpper ? kUpperCrownMm[i] : kLowerCrownMm[i];
}

std::vector<ArchLandmark> DetectToothLandmarks(const ToothView& view, double tooth_confidence) {
  std::vector<ArchLandmark> out;
  if (view.top.nx == 0) return out;
  const CrownBox box = Box(view);
  const int position = io::ToothPosition(view.fdi);
  if (position <= 2) {
    AddIncisalEdge(view, box, &out);
  } else if (position == 3) {
    AddCanineTip(view, box, &out);
  } else {
    AddTiltedCusps(view, box, &out);
  }
  if (position >= 4) AddCentralFossa(view, box, &out);
  AddContacts(view, box, &out);
  AddSurfacePoints(view, box, &out);
  for (ArchLandmark& l : out) l.confidence *= tooth_confidence;
  return out;
}

}  // namespace occlude::analysis
