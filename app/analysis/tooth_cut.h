// The cut between two neighbouring crowns of a single-surface scan, across the arch. Seen from
// the occlusal side the crowns meet along a valley (the occlusal embrasure over their contact,
// falling away into the buccal and lingual embrasures), and that valley runs across the arch
// curve at an angle when the crowns are rotated, tipped or offset from the curve (upper molars
// whose buccal contacts lie 1-2 mm mesial of their lingual ones): a cut is the path of least
// height across the crown band near a boundary the segmentation placed, arc length s as a
// function of the distance t across the curve (arch_curve.h's (s, t), mm).
#pragma once

#include <vector>

#include "arch_geometry.h"

namespace occlude::analysis {

struct ToothCut {
  double t0 = 0.0;          ///< t of the first sample, mm
  double step = 1.0;        ///< between samples along t, mm (> 0)
  std::vector<double> s{};  ///< arc length per sample, mm (non-empty)

  /// The cut's arc length at t (the end samples beyond its range).
  double At(double t) const;
};

/// A cut square to the curve at arc length s.
ToothCut StraightCut(double s);

/// The valley across the crown band near the boundary at arc length `s_mm` of g's curve: the
/// path over |t| <= kCutHalfSpanMm (sampled every cell of g.top) within `reach_mm` of s_mm
/// along the arc, turning by at most one cell per cell across, whose heights in g.top (empty
/// cells and cells far below the crowns counting as that floor) plus a cost per turn sum least.
ToothCut FindToothCut(const ArchGeometry& g, double s_mm, double reach_mm);

}  // namespace occlude::analysis
