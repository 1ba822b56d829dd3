// Orientation, occlusal view and arch curve of one jaw (arch_geometry.h).
#include "arch_geometry.h"

#include <algorithm>

#include "arch_opening.h"
#include "occlusal_plane.h"

namespace occlude::analysis {
namespace {

constexpr double kOpeningCellMm = 0.4;     // the outline needs no finer map
constexpr double kCentreDepthShare = 0.4;  // ray centre: this far from the opening to the front
constexpr double kBelowLocalTopMm = 4.0;   // crown cells: at most this below the local top
constexpr double kLocalTopRadiusMm = 4.0;  // within this

std::vector<Eigen::Vector2d> CrownPoints(const HeightMap& map, const std::vector<double>& crown) {
  std::vector<Eigen::Vector2d> points;
  for (int c = 0; c < map.nx * map.ny; ++c) {
    if (crown[static_cast<std::size_t>(c)] > 0.0) points.push_back(map.Centre(c));
  }
  return points;
}

}  // namespace

Eigen::Vector3d PatientLeft(io::Jaw jaw, const Eigen::Vector3d& occlusal,
                            const Eigen::Vector3d& anterior) {
  // J is right-handed; with y up and z anterior (the cases' frames), x = y x z is the left.
  const Eigen::Vector3d up = jaw == io::Jaw::kLower ? occlusal : Eigen::Vector3d(-occlusal);
  return up.cross(anterior).normalized();
}

std::optional<ArchGeometry> BuildArchGeometry(const io::TriangleMesh& mesh, io::Jaw jaw,
                                              const ArchAnalysisOptions& options,
                                              std::vector<std::string>* notes, std::string* why) {
  const OcclusalPlane plane = FindOcclusalPlane(mesh, options.grid_mm);
  if (!plane.note.empty()) notes->push_back(plane.note);
  ArchGeometry g;
  g.crown_floor = -options.crown_depth_mm;
  const ViewAxes first = AxesAround(plane.point_J, plane.up_J);
  const HeightMap coarse = RasterizeTop(mesh, {}, first, kOpeningCellMm);
  const std::vector<Eigen::Vector2d> outline =
      CrownPoints(coarse, CrownWeights(coarse, g.crown_floor, kBelowLocalTopMm, kLocalTopRadiusMm));
  const ArchOpening opening = FindArchOpening(outline);
  if (opening.confidence < 0.3) notes->push_back("the front of the arch is unclear");
  g.axes.origin_J = plane.point_J;
  g.axes.up_J = plane.up_J;
  g.axes.e2_J =
      (opening.anterior.x() * first.e1_J + opening.anterior.y() * first.e2_J).normalized();
  g.axes.e1_J = PatientLeft(jaw, g.axes.up_J, g.axes.e2_J);
  // For the upper jaw e1 = e2 x up: the view is mirrored, which leaves every plane distance
  // and the arch's order (right to left along +e1) as for the lower jaw.
  g.top = RasterizeTop(mesh, {}, g.axes, options.grid_mm);
  g.confidence = std::min(plane.confidence, opening.confidence);
  const Eigen::Vector2d middle = g.axes.Plane(first.Point(opening.middle, 0.0));
  g.crown = CrownWeights(g.top, g.crown_floor, kBelowLocalTopMm, kLocalTopRadiusMm);
  double depth = 0.0;
  for (const auto& p : CrownPoints(g.top, g.crown)) depth = std::max(depth, p.y() - middle.y());
  const Eigen::Vector2d centre = middle + Eigen::Vector2d(0.0, kCentreDepthShare * depth);
  std::optional<ArchCurve> curve = FitArchCurve(g.top, g.crown, centre, options.curve_step_mm, why);
  if (!curve) return std::nullopt;
  g.curve = std::move(*curve);
  g.cell_st.resize(g.top.height.size());
  for (int c = 0; c < g.top.nx * g.top.ny; ++c) {
    if (g.top.Filled(c)) g.cell_st[static_cast<std::size_t>(c)] = g.curve.Project(g.top.Centre(c));
  }
  g.vertex_st.reserve(mesh.num_vertices());
  for (const auto& v : mesh.vertices) g.vertex_st.push_back(g.curve.Project(g.axes.Plane(v)));
  return g;
}

}  // namespace occlude::analysis
