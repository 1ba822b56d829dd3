// The occlusal plane (occlusal_plane.h): principal axes of the surface, the side the crowns face,
// then a trimmed plane fit through the surface's local maxima, twice (the second time seen along
// the first fit's normal).
#include "occlusal_plane.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>

#include "geometry_util.h"

namespace occlude::analysis {
namespace {

constexpr double kMinViewCellMm = 0.4;  // coarsest maps are enough for the plane
constexpr double kPeakRadiusMm = 1.5;   // a cusp is the highest point this far around
constexpr double kPeakProminenceMm = 0.15;
constexpr double kPatchMm = 6.0;               // about a molar: each has cusps near its top
constexpr double kNearPatchTopMm = 1.0;        // peaks this close to their patch's top are cusps
constexpr double kTrimBelowMm[] = {3.0, 2.5};  // then: farther below the plane, gingiva

// How strongly the surface seen from axes.up looks like crowns: the share of the seen surface
// facing the viewer, squared, times its relief (spread of heights about their plane) + 0.5 mm.
double CrownScore(const io::TriangleMesh& mesh, const ViewAxes& axes, double cell) {
  const HeightMap map = RasterizeTop(mesh, {}, axes, cell);
  std::vector<Eigen::Vector3d> seen;
  double facing = 0.0;
  for (int c = 0; c < map.nx * map.ny; ++c) {
    if (!map.Filled(c)) continue;
    const auto t = static_cast<std::size_t>(map.triangle[static_cast<std::size_t>(c)]);
    if (mesh.face_normals[t].dot(axes.up_J) > 0.0) facing += 1.0;
    seen.push_back(map.Point_J(c));
  }
  if (seen.size() < 3) return 0.0;
  const Plane fit = FitPlane(seen);
  std::vector<double> r;
  r.reserve(seen.size());
  for (const auto& p : seen) r.push_back(fit.normal.dot(p - fit.point));
  const double relief = Quantile(r, 0.9) - Quantile(r, 0.1);
  const double share = facing / static_cast<double>(seen.size());
  return share * share * (relief + 0.5);
}

// Plane through the cusps: in each square patch of the view the peaks near the patch's highest
// one (so a tilted view cannot drop one side of the arch), fitted, then refitted without the
// peaks far below that plane (patches with gingiva only).
Plane FitCuspPlane(const std::vector<Eigen::Vector2d>& at, const std::vector<double>& height,
                   const std::vector<Eigen::Vector3d>& peaks, const Eigen::Vector3d& up, int* used,
                   double* rms) {
  std::map<std::pair<long, long>, double> highest;
  const auto patch = [&](std::size_t i) {
    return std::make_pair(static_cast<long>(std::floor(at[i].x() / kPatchMm)),
                          static_cast<long>(std::floor(at[i].y() / kPatchMm)));
  };
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    const auto [it, fresh] = highest.emplace(patch(i), height[i]);
    if (!fresh) it->second = std::max(it->second, height[i]);
  }
  std::vector<Eigen::Vector3d> kept;
  for (std::size_t i = 0; i < peaks.size(); ++i) {
    if (height[i] >= highest[patch(i)] - kNearPatchTopMm) kept.push_back(peaks[i]);
  }
  Plane plane = FitPlane(kept);
  for (const double below : kTrimBelowMm) {
    if (plane.normal.dot(up) < 0.0) plane.normal = -plane.normal;
    std::vector<Eigen::Vector3d> next;
    for (const auto& p : kept) {
      if (plane.normal.dot(p - plane.point) >= -below) next.push_back(p);
    }
    if (next.size() < 3) break;
    kept = std::move(next);
    plane = FitPlane(kept);
  }
  if (plane.normal.dot(up) < 0.0) plane.normal = -plane.normal;
  double sum = 0.0;
  for (const auto& p : kept) sum += std::pow(plane.normal.dot(p - plane.point), 2);
  *used = static_cast<int>(kept.size());
  *rms = kept.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(kept.size()));
  return plane;
}

}  // namespace

std::vector<int> HeightPeaks(const HeightMap& map, double radius_mm, double prominence_mm) {
  const int r = std::max(1, static_cast<int>(std::lround(radius_mm / map.cell)));
  std::vector<int> peaks;
  for (int j = 0; j < map.ny; ++j) {
    for (int i = 0; i < map.nx; ++i) {
      const int c = map.Index(i, j);
      if (!map.Filled(c)) continue;
      const double h = map.height[static_cast<std::size_t>(c)];
      bool top = true;
      double sum = 0.0;
      int n = 0;
      for (int dj = -r; dj <= r && top; ++dj) {
        for (int di = -r; di <= r; ++di) {
          const int ii = i + di, jj = j + dj;
          if (ii < 0 || jj < 0 || ii >= map.nx || jj >= map.ny) continue;
          const double g = map.height[static_cast<std::size_t>(map.Index(ii, jj))];
          if (std::isnan(g)) continue;
          // Ties go to the first cell in scan order, so a plateau gives one peak.
          if (g > h || (g == h && (jj < j || (jj == j && ii < i)))) {
            top = false;
            break;
          }
          sum += g;
          ++n;
        }
      }
      if (top && n > 1 && h - sum / n >= prominence_mm) peaks.push_back(c);
    }
  }
  return peaks;
}

OcclusalPlane FindOcclusalPlane(const io::TriangleMesh& mesh, double cell) {
  const double view_cell = std::max(cell, kMinViewCellMm);
  const PrincipalAxes pca = SurfacePrincipalAxes(mesh, {});
  OcclusalPlane out;
  const double up_score = CrownScore(mesh, AxesAround(pca.centre, pca.axes.col(0)), view_cell);
  const double down_score = CrownScore(mesh, AxesAround(pca.centre, -pca.axes.col(0)), view_cell);
  Eigen::Vector3d up = up_score >= down_score ? pca.axes.col(0) : Eigen::Vector3d(-pca.axes.col(0));
  const double best = std::max(up_score, down_score);
  out.confidence = best > 0.0 ? std::abs(up_score - down_score) / best : 0.0;
  if (out.confidence < 0.3) out.note = "the occlusal side of the jaw is unclear";
  Eigen::Vector3d point = pca.centre;
  for (int pass = 0; pass < 2; ++pass) {
    const HeightMap map = RasterizeTop(mesh, {}, AxesAround(point, up), view_cell);
    std::vector<Eigen::Vector3d> peaks;
    std::vector<Eigen::Vector2d> at;
    std::vector<double> height;
    for (const int c : HeightPeaks(map, kPeakRadiusMm, kPeakProminenceMm)) {
      peaks.push_back(map.Point_J(c));
      at.push_back(map.Centre(c));
      height.push_back(map.height[static_cast<std::size_t>(c)]);
    }
    if (peaks.size() < 3) break;
    const Plane plane = FitCuspPlane(at, height, peaks, up, &out.cusps, &out.rms_mm);
    up = plane.normal;
    point = plane.point;
  }
  out.point_J = point;
  out.up_J = up;
  return out;
}

}  // namespace occlude::analysis
