// One tooth as the landmark detection sees it: its crown seen from the occlusal side (a small
// height map with per-cell arch coordinates) and its surface vertices, in tooth coordinates
// (u, v, w): u along the arch towards the midline (mesial, mm from the tooth's middle), v across
// it outward (buccal / labial), w the height along the occlusal axis (0 on the occlusal plane).
// A tooth cut out of a single surface lies between two cuts that may run obliquely across the
// arch (tooth_cut.h): its ends are at u_mesial and u_distal on the curve (v = 0) and at EndU
// elsewhere.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "arch_analysis.h"
#include "arch_geometry.h"
#include "height_map.h"
#include "tooth_cut.h"

namespace occlude::analysis {

struct ToothView {
  int fdi = 0;
  io::Jaw jaw = io::Jaw::kLower;
  HeightMap top;  ///< the crown seen along the occlusal axis (other cells NaN)
  std::vector<Eigen::Vector3d> top_uvw;    ///< per cell of `top` (filled ones meaningful)
  std::vector<Eigen::Vector3d> surface_J;  ///< the tooth's vertices (crown part of a scan)
  std::vector<Eigen::Vector3d> surface_uvw;
  /// The mesh's triangles with all three vertices in the view (indices into surface_J).
  std::vector<std::array<std::int32_t, 3>> surface_triangles;
  double u_mesial = 0.0, u_distal = 0.0;  ///< u of its boundaries (u_mesial > 0 > u_distal)
  bool whole_crown = false;  ///< a separate shell or part: its proximal surfaces are real

  double s_mid = 0.0;        ///< arc length of u = 0 (at v = 0)
  double mesial_sign = 1.0;  ///< +1 when mesial is increasing s (right side), else -1
  /// Segmented teeth: the cuts on the patient's right and left (arc length as a function of v);
  /// empty for whole crowns, whose u is the arc length from s_mid.
  ToothCut right_cut, left_cut;
  /// The direction of the row of teeth at this tooth, dv/du in its tooth coordinates: the line
  /// through its neighbours' crowns (SetArchSlopes); 0 along the curve.
  double arch_slope = 0.0;
};

/// +1 for the teeth of the patient's right (mesial is towards increasing arc length), else -1.
double MesialSign(int fdi);

/// The u of the view's mesial (or distal) end at v: its cut there, else u_mesial (u_distal).
double EndU(const ToothView& view, double v, bool mesial);

/// Tooth coordinates of a point in J, for a tooth with middle s_mid and mesial_sign.
Eigen::Vector3d ToothCoordinates(const ArchGeometry& g, double s_mid, double mesial_sign,
                                 const Eigen::Vector3d& p_J);

/// The view of a tooth cut out of the whole jaw's occlusal view between the cuts `right` and
/// `left` (segmented scans; right.At(t) < left.At(t)): the cells of g.top between them and
/// within `half_width_mm` of the curve, and the mesh vertices likewise (g.vertex_st) within
/// `depth_mm` below the tooth's top.
ToothView SegmentedToothView(const io::TriangleMesh& mesh, const ArchGeometry& g, int fdi,
                             io::Jaw jaw, const ToothCut& right, const ToothCut& left,
                             double half_width_mm, double depth_mm);

/// Sets each view's arch_slope (views in arch order; `next_is_neighbour[k]` when views k and k + 1
/// stand next to each other): the direction from the centre of the crown before it to that of
/// the crown after it (its own centre for a missing neighbour; unchanged without either), a
/// crown's centre the middle of its cells within 3 mm of its top, the slope at most 0.5. The arch
/// curve is a smooth fit through the crown band: where the teeth's row runs turned from it (a
/// narrow incisor segment, the premolars, the last molars), a line across a crown square to the
/// curve is turned from the tooth's own facial-lingual line.
void SetArchSlopes(const ArchGeometry& g, const std::vector<bool>& next_is_neighbour,
                   std::vector<ToothView>* views);

/// The view of a tooth given as its own triangles (a part or a shell).
ToothView ShellToothView(const io::TriangleMesh& mesh, const ArchGeometry& g, int fdi, io::Jaw jaw,
                         const std::vector<std::int32_t>& triangles);

}  // namespace occlude::analysis
