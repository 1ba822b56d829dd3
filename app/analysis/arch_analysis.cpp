// AnalyzeArch (arch_analysis.h): the jaw's geometry (arch_geometry.h), its teeth
// (tooth_regions.h), each tooth's landmarks (tooth_landmarks.h), then the frame and midline.
#include "arch_analysis.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "analysis_code_hash.h"
#include "arch_geometry.h"
#include "tooth_landmarks.h"
#include "tooth_regions.h"
#include "tooth_view.h"

namespace occlude::analysis {
namespace {

constexpr double kToothHalfWidthMm = 7.0;  // a segmented tooth: this far across the curve ...
constexpr double kToothDepthMm = 9.0;      // ... and this far below its top

void CheckOptions(const ArchAnalysisOptions& o) {
  const auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument(std::string(name) + ": " + std::to_string(v) +
                                  " must be a positive number of millimetres");
    }
  };
  positive(o.grid_mm, "grid_mm");
  positive(o.curve_step_mm, "curve_step_mm");
  positive(o.crown_depth_mm, "crown_depth_mm");
}

ToothView ViewOf(const io::TriangleMesh& mesh, const ArchGeometry& g, const ToothRegion& r,
                 io::Jaw jaw) {
  if (r.source == ToothSource::kSegmented) {
    return SegmentedToothView(mesh, g, r.fdi, jaw, r.right_cut, r.left_cut, kToothHalfWidthMm,
                              kToothDepthMm);
  }
  return ShellToothView(mesh, g, r.fdi, jaw, r.triangles);
}

// Two teeth next to each other in one arch (11 and 21, 41 and 31 across the midline).
bool Neighbours(int fdi_a, int fdi_b) {
  const int pa = io::ToothPosition(fdi_a), pb = io::ToothPosition(fdi_b);
  if (fdi_a / 10 == fdi_b / 10) return std::abs(pa - pb) == 1;
  return pa == 1 && pb == 1;
}

ArchTooth Summarize(const ToothRegion& r, const ToothView& view) {
  ArchTooth t;
  t.fdi = r.fdi;
  t.source = r.source;
  t.confidence = r.confidence;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (int c = 0; c < view.top.nx * view.top.ny; ++c) {
    if (view.top.Filled(c)) sum += view.top.Point_J(c), ++n;
  }
  t.centre_J = n > 0 ? Eigen::Vector3d(sum / n) : sum;
  const double a = view.s_mid + view.mesial_sign * view.u_mesial;
  const double b = view.s_mid + view.mesial_sign * view.u_distal;
  t.mesial_mm = a;
  t.distal_mm = b;
  return t;
}

// The frame from the geometry; the midline between the central incisors' mesial contacts when
// both were found, else on the curve at its mirror axis.
void SetFrame(const ArchGeometry& g, ArchAnalysis* out) {
  out->frame.lateral_J = g.axes.e1_J;
  out->frame.anterior_J = g.axes.e2_J;
  out->frame.occlusal_J = g.axes.up_J;
  const int right = out->jaw == io::Jaw::kUpper ? 11 : 41;
  const int left = out->jaw == io::Jaw::kUpper ? 21 : 31;
  const ArchLandmark* a = out->Find(right, io::LandmarkType::kMesial);
  const ArchLandmark* b = out->Find(left, io::LandmarkType::kMesial);
  const double s = g.curve.symmetry_s;
  out->midline_J = (a && b) ? Eigen::Vector3d(0.5 * (a->landmark.p + b->landmark.p))
                            : g.axes.Point(g.curve.At(s), g.curve.TopAt(s));
  out->frame.origin_J =
      out->midline_J - g.axes.up_J.dot(out->midline_J - g.axes.origin_J) * g.axes.up_J;
}

}  // namespace

const char* ToString(ToothSource source) {
  switch (source) {
    case ToothSource::kParts:
      return "parts";
    case ToothSource::kComponents:
      return "components";
    default:
      return "segmented";
  }
}

const char* ToString(LandmarkSource source) {
  return source == LandmarkSource::kGiven ? "given" : "detected";
}

const ArchLandmark* ArchAnalysis::Find(int fdi, io::LandmarkType type) const {
  for (const ArchLandmark& l : landmarks) {
    if (l.landmark.tooth_fdi == fdi && l.landmark.type == type) return &l;
  }
  return nullptr;
}

std::vector<io::Landmark> ArchAnalysis::Points() const {
  std::vector<io::Landmark> points;
  for (const ArchLandmark& l : landmarks) points.push_back(l.landmark);
  return points;
}

const char* ArchAnalysisCodeVersion() { return kAnalysisCodeHash; }

ArchAnalysis AnalyzeArch(const io::TriangleMesh& jaw_J, io::Jaw which,
                         const ArchAnalysisOptions& options) {
  CheckOptions(options);
  ArchAnalysis out;
  out.jaw = which;
  const std::string name = std::string("the ") + io::ToString(which) + " jaw";
  if (jaw_J.empty()) {
    out.error = name + " has no triangles";
    return out;
  }
  std::string why;
  const std::optional<ArchGeometry> g = BuildArchGeometry(jaw_J, which, options, &out.notes, &why);
  if (!g) {
    out.error = "no tooth found on " + name + ": " + why;
    return out;
  }
  for (std::size_t k = 0; k < g->curve.q.size(); ++k) {
    out.arch_curve_J.push_back(g->axes.Point(g->curve.q[k], g->curve.top[k]));
  }
  const std::vector<ToothRegion> regions = FindTeeth(jaw_J, *g, which, &out.notes, &why);
  if (regions.empty()) {
    out.error = "no tooth found on " + name + ": " + why;
    SetFrame(*g, &out);
    return out;
  }
  std::vector<ToothView> views;
  std::vector<bool> next_is_neighbour;
  for (std::size_t k = 0; k < regions.size(); ++k) {
    views.push_back(ViewOf(jaw_J, *g, regions[k], which));
    if (k > 0) next_is_neighbour.push_back(Neighbours(regions[k - 1].fdi, regions[k].fdi));
  }
  SetArchSlopes(*g, next_is_neighbour, &views);
  for (std::size_t k = 0; k < regions.size(); ++k) {
    out.teeth.push_back(Summarize(regions[k], views[k]));
    for (ArchLandmark& l : DetectToothLandmarks(views[k], regions[k].confidence)) {
      out.landmarks.push_back(std::move(l));
    }
  }
  for (std::size_t k = 0; k + 1 < views.size(); ++k) {
    if (Neighbours(views[k].fdi, views[k + 1].fdi)) {
      PlaceContacts(views[k], views[k + 1],
                    std::min(regions[k].confidence, regions[k + 1].confidence), &out.landmarks);
    }
  }
  SetFrame(*g, &out);
  return out;
}

void ApplyGivenLandmarks(const std::vector<io::Landmark>& given, ArchAnalysis* analysis) {
  for (const io::Landmark& g : given) {
    if (g.jaw != analysis->jaw) continue;
    ArchLandmark l;
    l.landmark = g;
    l.source = LandmarkSource::kGiven;
    l.confidence = 1.0;
    l.method = "given";
    bool replaced = false;
    for (ArchLandmark& d : analysis->landmarks) {
      if (d.landmark.tooth_fdi == g.tooth_fdi && d.landmark.type == g.type) {
        d = l;
        replaced = true;
      }
    }
    if (!replaced) analysis->landmarks.push_back(l);
  }
}

}  // namespace occlude::analysis
