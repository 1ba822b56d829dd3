// The report's pictures (see report_images.h): rasterized views, decorated
// with OpenCV (text, legend, markers), encoded as PNG.
#include "report/report_images.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "base/png_writer.h"

namespace occlude::app {
namespace {

constexpr int kSupersample = 2;
constexpr int kTitleHeight = 46;
constexpr int kLegendWidth = 250;
constexpr int kMargin = 28;
// Tooth numbers sit this far outward from the crown's centroid (about a crown's half width + 2 mm).
constexpr double kToothLabelOffsetMm = 7.0;
constexpr render::Rgb kLowerTint = {232, 224, 200};
constexpr render::Rgb kUpperTint = {196, 214, 236};
const cv::Scalar kBlack(0, 0, 0), kWhite(255, 255, 255), kGrey(90, 90, 90);

cv::Scalar Cv(render::Rgb c) { return cv::Scalar(c[0], c[1], c[2]); }

// Canvas channels are RGB throughout; EncodePng swaps to OpenCV's BGR.
cv::Mat ToMat(const render::Image& img) {
  cv::Mat m(img.height, img.width, CV_8UC3);
  std::copy(img.rgb.begin(), img.rgb.end(), m.data);
  return m;
}

render::Image FromMat(const cv::Mat& m) {
  render::Image img(m.cols, m.rows, render::kBackground);
  std::copy(m.data, m.data + img.rgb.size(), img.rgb.begin());
  return img;
}

void Text(cv::Mat* m, const std::string& s, cv::Point at, double scale, const cv::Scalar& colour,
          int thickness = 1, bool halo = false) {
  if (halo)
    cv::putText(*m, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, kWhite, thickness + 3, cv::LINE_AA);
  cv::putText(*m, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, thickness, cv::LINE_AA);
}

void CentredText(cv::Mat* m, const std::string& s, cv::Point2d centre, double scale,
                 const cv::Scalar& colour, int thickness, bool halo) {
  int base = 0;
  const cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &base);
  Text(m, s,
       cv::Point(static_cast<int>(centre.x) - size.width / 2,
                 static_cast<int>(centre.y) + size.height / 2),
       scale, colour, thickness, halo);
}

std::string Mm(double v, int decimals = 2) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(decimals);
  s << v;
  return s.str();
}

// Every k-th vertex of a mesh at a pose (for framing a view).
void AddPoints(const io::TriangleMesh& mesh, const Eigen::Isometry3d& X,
               std::vector<Eigen::Vector3d>* out) {
  const std::size_t step = std::max<std::size_t>(1, mesh.num_vertices() / 20000);
  for (std::size_t i = 0; i < mesh.num_vertices(); i += step) out->push_back(X * mesh.vertices[i]);
}

// A view of `width` pixels framing the points, as tall as their aspect needs.
render::OrthoView FitToWidth(const Eigen::Vector3d& view, const Eigen::Vector3d& up,
                             const std::vector<Eigen::Vector3d>& pts, int width, int min_h,
                             int max_h) {
  render::OrthoView v = render::FitView(view, up, pts, width, 100000, kMargin);
  double lo = 1e300, hi = -1e300;
  for (const auto& p : pts) {
    lo = std::min(lo, p.dot(v.up_L));
    hi = std::max(hi, p.dot(v.up_L));
  }
  const int h = std::clamp(static_cast<int>((hi - lo) * v.px_per_mm) + 2 * kMargin, min_h, max_h);
  return render::FitView(view, up, pts, width, h, kMargin);
}

template <typename Colour>
render::Image Draw(const render::OrthoView& view, const std::vector<render::Surface>& surfaces,
                   const Colour& colour) {
  render::OrthoView ss = view.Scaled(kSupersample);
  return render::Resolve(render::Rasterize(ss, surfaces), colour, render::kBackground,
                         kSupersample);
}

double ScaleBarMm(double px_per_mm) {
  double mm = 10.0;
  while (mm * px_per_mm > 180 && mm > 1) mm /= 2;
  return mm;
}

// A bar ScaleBarMm long with end ticks and its label, bottom-left at `at`.
void ScaleBar(cv::Mat* m, cv::Point at, double px_per_mm) {
  const double mm = ScaleBarMm(px_per_mm);
  const int len = static_cast<int>(std::lround(mm * px_per_mm));
  cv::line(*m, at, at + cv::Point(len, 0), kBlack, 3);
  cv::line(*m, at + cv::Point(0, -7), at + cv::Point(0, 7), kBlack, 2);
  cv::line(*m, at + cv::Point(len, -7), at + cv::Point(len, 7), kBlack, 2);
  Text(m, Mm(mm, mm < 10 ? 1 : 0) + " mm", at + cv::Point(len + 10, 6), 0.55, kBlack);
}

void Swatch(cv::Mat* m, cv::Point at, render::Rgb colour, const std::string& label) {
  cv::rectangle(*m, cv::Rect(at.x, at.y, 28, 18), Cv(colour), cv::FILLED);
  cv::rectangle(*m, cv::Rect(at.x, at.y, 28, 18), kGrey, 1);
  Text(m, label, at + cv::Point(38, 14), 0.5, kBlack);
}

// The colour legend with the mm scale, contact band, penetration and far colours.
int Legend(cv::Mat* m, int x, int y, const render::MapScale& s, std::size_t spots) {
  Text(m, "Distance to the", {x, y}, 0.55, kBlack, 1);
  Text(m, "opposing arch (mm)", {x, y + 22}, 0.55, kBlack, 1);
  y += 44;
  Swatch(m, {x, y}, render::kPenetrationColour,
         "penetration > " + Mm(s.penetration_from_mm) + " mm");
  y += 34;
  const int bar_h = 280, bar_w = 32;
  for (int r = 0; r < bar_h; ++r) {
    const double d = s.max_mm * r / (bar_h - 1);
    cv::line(*m, {x, y + r}, {x + bar_w, y + r}, Cv(render::DistanceColour(d, s)));
  }
  cv::rectangle(*m, cv::Rect(x, y, bar_w, bar_h), kGrey, 1);
  const double step = s.max_mm <= 1.0 ? 0.1 : (s.max_mm <= 2.5 ? 0.25 : 0.5);
  for (double d = 0; d <= s.max_mm + 1e-9; d += step) {
    const int yy = y + static_cast<int>(std::lround(d / s.max_mm * (bar_h - 1)));
    cv::line(*m, {x + bar_w, yy}, {x + bar_w + 6, yy}, kBlack, 1);
    Text(m, Mm(d, step < 0.25 ? 1 : 2), {x + bar_w + 10, yy + 5}, 0.48, kBlack);
  }
  const int band_y =
      y + static_cast<int>(std::lround(std::min(1.0, s.band_mm / s.max_mm) * (bar_h - 1)));
  const int bx = x + bar_w + 62;
  cv::line(*m, {bx, y}, {bx, band_y}, kBlack, 2);
  cv::line(*m, {bx - 5, y}, {bx, y}, kBlack, 2);
  cv::line(*m, {bx - 5, band_y}, {bx, band_y}, kBlack, 2);
  Text(m, "contact", {bx + 6, (y + band_y) / 2 - 2}, 0.48, kBlack);
  Text(m, "0-" + Mm(s.band_mm) + " mm", {bx + 6, (y + band_y) / 2 + 16}, 0.45, kBlack);
  y += bar_h + 16;
  Swatch(m, {x, y}, render::kFarColour, "> " + Mm(s.max_mm) + " mm (open)");
  y += 32;
  cv::circle(*m, {x + 14, y + 9}, 10, kBlack, 1, cv::LINE_AA);
  Text(m, "contact spot (" + std::to_string(spots) + ")", {x + 38, y + 14}, 0.5, kBlack);
  return y + 30;
}

// Centroid in L of each tooth part's vertices, with its number.
std::vector<std::pair<int, Eigen::Vector3d>> ToothCentroids(const io::TriangleMesh& mesh,
                                                            const Eigen::Isometry3d& X) {
  std::vector<Eigen::Vector3d> sum(mesh.parts.size(), Eigen::Vector3d::Zero());
  std::vector<double> count(mesh.parts.size(), 0.0);
  for (std::size_t t = 0; t < mesh.num_triangles() && !mesh.triangle_part.empty(); ++t) {
    const auto p = static_cast<std::size_t>(mesh.triangle_part[t]);
    if (p >= mesh.parts.size() || mesh.parts[p].tooth_number <= 0) continue;
    sum[p] += (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
    count[p] += 1;
  }
  std::vector<std::pair<int, Eigen::Vector3d>> out;
  for (std::size_t p = 0; p < sum.size(); ++p) {
    if (count[p] > 0) out.emplace_back(mesh.parts[p].tooth_number, X * (sum[p] / count[p]));
  }
  return out;
}

void SideLabels(cv::Mat* m, const render::OrthoView& v, const collision::ArchFrame& arch, int x0,
                int y0, int w, int h) {
  const bool right_is_left = v.right_L.dot(arch.lateral_L) > 0;
  CentredText(m, right_is_left ? "R" : "L", {x0 + 14.0, y0 + h / 2.0}, 0.9, kGrey, 2, false);
  CentredText(m, right_is_left ? "L" : "R", {x0 + w - 14.0, y0 + h / 2.0}, 0.9, kGrey, 2, false);
}

}  // namespace

MapImage RenderContactMap(Arch arch, const JawPair& jaws, const ReportAnalysis& a,
                          const render::MapScale& scale, int width_px) {
  const bool upper = arch == Arch::kUpper;
  const io::TriangleMesh& mesh = upper ? *jaws.upper_U : *jaws.lower_L;
  const Eigen::Isometry3d X = upper ? a.X_LU : Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3d> pts;  // both arches, so the two maps share one scale
  AddPoints(*jaws.lower_L, Eigen::Isometry3d::Identity(), &pts);
  AddPoints(*jaws.upper_U, a.X_LU, &pts);
  const int map_w = width_px - kLegendWidth;
  const Eigen::Vector3d view = upper ? a.arch.occlusal_L : Eigen::Vector3d(-a.arch.occlusal_L);
  MapImage out;
  out.view = FitToWidth(view, a.arch.anterior_L, pts, map_w, 420, 1600);
  const render::Image map =
      Draw(out.view, {{&mesh, X, upper ? &a.upper_vertex_mm : &a.lower_vertex_mm, 0}},
           [&](int, float d) { return render::DistanceColour(d, scale); });
  const int height = kTitleHeight + std::max(map.height, 560);
  cv::Mat canvas(height, width_px, CV_8UC3, kWhite);
  ToMat(map).copyTo(canvas(cv::Rect(0, kTitleHeight, map.width, map.height)));
  out.view.offset_px = Eigen::Vector2d(0, kTitleHeight);
  out.map_x = 0;
  out.map_y = kTitleHeight;
  out.map_width = map.width;
  out.map_height = map.height;

  Text(&canvas,
       upper ? "Upper arch from below: distance to the lower arch"
             : "Lower arch from above: distance to the upper arch",
       {14, 30}, 0.72, kBlack, 2);
  CentredText(&canvas, "anterior", {map_w / 2.0, kTitleHeight + 14.0}, 0.55, kGrey, 1, false);
  SideLabels(&canvas, out.view, a.arch, 0, kTitleHeight, map_w, map.height);
  for (const auto& spot : a.spots) {
    const Eigen::Vector2d px = out.view.ToPixel(spot.p_L);
    cv::circle(canvas, cv::Point(static_cast<int>(px.x()), static_cast<int>(px.y())), 10, kBlack, 1,
               cv::LINE_AA);
  }
  // Tooth numbers beside the crowns, on the buccal/labial side (radially out from
  // the arch's centre), so they never cover the occlusal surface.
  const auto teeth = ToothCentroids(mesh, X);
  Eigen::Vector2d arch_centre = Eigen::Vector2d::Zero();
  for (const auto& t : teeth)
    arch_centre += out.view.ToPixel(t.second) / static_cast<double>(teeth.size());
  for (const auto& [tooth, c] : teeth) {
    const Eigen::Vector2d px = out.view.ToPixel(c);
    const Eigen::Vector2d dir = (px - arch_centre).norm() > 1
                                    ? Eigen::Vector2d((px - arch_centre).normalized())
                                    : Eigen::Vector2d(0, -1);
    const Eigen::Vector2d at = px + dir * (kToothLabelOffsetMm * out.view.px_per_mm);
    CentredText(&canvas, std::to_string(tooth), {at.x(), at.y()}, 0.6, kBlack, 2, true);
  }
  const int lx = map_w + 12;
  const int y = Legend(&canvas, lx, kTitleHeight + 24, scale, a.spots.size());
  ScaleBar(&canvas, {lx, std::min(y + 20, height - 20)}, out.view.px_per_mm);
  out.image = FromMat(canvas);
  return out;
}

render::Image RenderSideView(SideView side, const JawPair& jaws, const ReportAnalysis& a,
                             const render::MapScale& scale, int width_px) {
  std::vector<Eigen::Vector3d> pts;
  AddPoints(*jaws.lower_L, Eigen::Isometry3d::Identity(), &pts);
  AddPoints(*jaws.upper_U, a.X_LU, &pts);
  const bool frontal = side == SideView::kFrontal;
  const Eigen::Vector3d view = frontal ? Eigen::Vector3d(-a.arch.anterior_L) : a.arch.lateral_L;
  const render::OrthoView v = FitToWidth(view, a.arch.occlusal_L, pts, width_px, 240, 900);
  const auto colour = [&](int id, float value) {
    const double d = value;
    if (d < -scale.penetration_from_mm || d <= scale.max_mm)
      return render::DistanceColour(d, scale);
    return id == 1 ? kUpperTint : kLowerTint;
  };
  const render::Image img =
      Draw(v,
           {{jaws.lower_L.get(), Eigen::Isometry3d::Identity(), &a.lower_vertex_mm, 0},
            {jaws.upper_U.get(), a.X_LU, &a.upper_vertex_mm, 1}},
           colour);
  cv::Mat canvas(img.height + kTitleHeight + 40, width_px, CV_8UC3, kWhite);
  ToMat(img).copyTo(canvas(cv::Rect(0, kTitleHeight, img.width, img.height)));
  Text(&canvas,
       frontal ? "Frontal view (from the front)" : "Right lateral view (anterior to the right)",
       {14, 30}, 0.72, kBlack, 2);
  if (frontal) SideLabels(&canvas, v, a.arch, 0, kTitleHeight, width_px, img.height);
  const int by = kTitleHeight + img.height + 22;
  Swatch(&canvas, {14, by - 12}, kUpperTint, "upper jaw");
  Swatch(&canvas, {170, by - 12}, kLowerTint, "lower jaw");
  Text(&canvas, "near-contact surfaces in the map colours", {330, by + 2}, 0.48, kGrey);
  ScaleBar(&canvas, {width_px - 80 - static_cast<int>(ScaleBarMm(v.px_per_mm) * v.px_per_mm), by},
           v.px_per_mm);
  return FromMat(canvas);
}

namespace {

// Short names of the landmark types for labels (the legend spells them out).
const char* TypeAbbreviation(io::LandmarkType type) {
  static const char* const kNames[io::kNumLandmarkTypes] = {
      "m", "d", "f", "l", "ie", "ct", "bc", "lc", "mb", "mbc", "db", "ml", "dl", "cf"};
  return kNames[static_cast<int>(type)];
}

void LandmarkMarker(cv::Mat* m, cv::Point c, bool given) {
  constexpr int kRadius = 5;
  if (given) {
    const cv::Rect box(c.x - kRadius, c.y - kRadius, 2 * kRadius + 1, 2 * kRadius + 1);
    cv::rectangle(*m, box, Cv(kGivenLandmarkColour), cv::FILLED);
    cv::rectangle(*m, box, kBlack, 1);
  } else {
    cv::circle(*m, c, kRadius + 1, kBlack, cv::FILLED, cv::LINE_AA);
    cv::circle(*m, c, kRadius, Cv(kDetectedLandmarkColour), cv::FILLED, cv::LINE_AA);
  }
}

// One arch's panel: the mesh shaded in its tint, its landmarks' labels, then their markers (on
// top, so no label hides one); returns the panel and fills `px` of its landmarks.
cv::Mat LandmarkPanel(bool upper, const JawPair& jaws, const Eigen::Isometry3d& X_LU,
                      const std::vector<analysis::ArchLandmark>& landmarks_L,
                      const collision::ArchFrame& frame, int width_px,
                      std::vector<Eigen::Vector2d>* px) {
  const io::TriangleMesh& mesh = upper ? *jaws.upper_U : *jaws.lower_L;
  const Eigen::Isometry3d X = upper ? X_LU : Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3d> pts;
  AddPoints(mesh, X, &pts);
  const Eigen::Vector3d view = upper ? frame.occlusal_L : Eigen::Vector3d(-frame.occlusal_L);
  render::OrthoView v = FitToWidth(view, frame.anterior_L, pts, width_px, 420, 1600);
  const render::Rgb tint = upper ? kUpperTint : kLowerTint;
  const render::Image img = Draw(v, {{&mesh, X, nullptr, 0}}, [&](int, float) { return tint; });
  cv::Mat panel(img.height + kTitleHeight, width_px, CV_8UC3, kWhite);
  ToMat(img).copyTo(panel(cv::Rect(0, kTitleHeight, img.width, img.height)));
  v.offset_px = Eigen::Vector2d(0, kTitleHeight);
  Text(&panel, upper ? "Upper arch from below" : "Lower arch from above", {14, 30}, 0.72, kBlack,
       2);
  CentredText(&panel, "anterior", {width_px / 2.0, kTitleHeight + 14.0}, 0.55, kGrey, 1, false);
  SideLabels(&panel, v, frame, 0, kTitleHeight, width_px, img.height);
  const io::Jaw jaw = upper ? io::Jaw::kUpper : io::Jaw::kLower;
  std::vector<std::pair<cv::Point, bool>> markers;
  for (std::size_t i = 0; i < landmarks_L.size(); ++i) {
    const io::Landmark& l = landmarks_L[i].landmark;
    if (l.jaw != jaw) continue;
    (*px)[i] = v.ToPixel(l.p);
    const cv::Point c(static_cast<int>(std::lround((*px)[i].x())),
                      static_cast<int>(std::lround((*px)[i].y())));
    Text(&panel, std::to_string(l.tooth_fdi) + " " + TypeAbbreviation(l.type), c + cv::Point(8, 4),
         0.36, kBlack, 1, true);
    markers.emplace_back(c, landmarks_L[i].source == analysis::LandmarkSource::kGiven);
  }
  for (const auto& [c, given] : markers) LandmarkMarker(&panel, c, given);
  ScaleBar(&panel, {14, kTitleHeight + img.height - 16}, v.px_per_mm);
  return panel;
}

// The markers and the type abbreviations.
cv::Mat LandmarkLegend(int width_px) {
  cv::Mat m(96, width_px, CV_8UC3, kWhite);
  LandmarkMarker(&m, {24, 20}, false);
  Text(&m, "detected", {38, 25}, 0.5, kBlack);
  LandmarkMarker(&m, {144, 20}, true);
  Text(&m, "given (landmark file)", {158, 25}, 0.5, kBlack);
  std::string names;
  for (int t = 0; t < io::kNumLandmarkTypes; ++t) {
    const auto type = static_cast<io::LandmarkType>(t);
    names +=
        std::string(names.empty() ? "" : ", ") + TypeAbbreviation(type) + " " + io::ToString(type);
    if (t == 6 || t == io::kNumLandmarkTypes - 1) {
      Text(&m, names, {14, t == 6 ? 56 : 82}, 0.45, kGrey);
      names.clear();
    }
  }
  return m;
}

}  // namespace

LandmarkImage RenderLandmarkMap(const JawPair& jaws, const Eigen::Isometry3d& X_LU,
                                const std::vector<analysis::ArchLandmark>& landmarks_L,
                                const analysis::ArchFrame& frame_L, int width_px) {
  collision::ArchFrame frame;
  frame.origin_L = frame_L.origin_J;
  frame.occlusal_L = frame_L.occlusal_J;
  frame.anterior_L = frame_L.anterior_J;
  frame.lateral_L = frame_L.lateral_J;
  LandmarkImage out;
  out.px.assign(landmarks_L.size(), Eigen::Vector2d::Zero());
  const cv::Mat lower = LandmarkPanel(false, jaws, X_LU, landmarks_L, frame, width_px, &out.px);
  std::vector<Eigen::Vector2d> upper_px(landmarks_L.size(), Eigen::Vector2d::Zero());
  const cv::Mat upper = LandmarkPanel(true, jaws, X_LU, landmarks_L, frame, width_px, &upper_px);
  for (std::size_t i = 0; i < landmarks_L.size(); ++i) {
    if (landmarks_L[i].landmark.jaw == io::Jaw::kUpper) {
      out.px[i] = upper_px[i] + Eigen::Vector2d(0, lower.rows);
    }
  }
  cv::Mat canvas;
  cv::vconcat(std::vector<cv::Mat>{lower, upper, LandmarkLegend(width_px)}, canvas);
  out.image = FromMat(canvas);
  return out;
}

std::string EncodePng(const render::Image& image) {
  return EncodePng(image.rgb.data(), image.width, image.height, PngPixels::kRgb,
                   3 * static_cast<std::size_t>(image.width));
}

}  // namespace occlude::app
