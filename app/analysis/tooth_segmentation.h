// Teeth cut out of a single-surface scan along the arch curve. Between two crowns the surface
// dips on all sides (occlusal, buccal and lingual embrasures), so the crown material above a
// floor, summed across the arch at each arc length, has a valley at every boundary. A dynamic
// programme places the boundaries at valleys, with the teeth in FDI order outward from a
// midline near the arch's apex and widths near the typical widths of their positions (one
// scale per arch, 6-8 teeth per side).
#pragma once

#include <string>
#include <vector>

#include "arch_curve.h"
#include "height_map.h"
#include "occlude/io/dental.h"

namespace occlude::analysis {

/// A tooth's extent along the arch curve.
struct ToothSpan {
  int fdi = 0;
  double s_lo = 0.0, s_hi = 0.0;  ///< arc length of its right and left boundaries, mm
  double confidence = 0.0;        ///< in [0, 1]
};

/// The crown profile along the curve, per station (every curve.step), of the crown cells within
/// `half_width_mm` of the curve.
struct CrownProfile {
  std::vector<double> material;  ///< their height above the floor, mm^2 per mm of arc
  std::vector<double> weight;    ///< their CrownWeights, mm^4 per mm of arc
};
/// The profile of the view `map` (crown weights `crown`, cells' curve coordinates `cell_st`).
CrownProfile MakeCrownProfile(const HeightMap& map, const std::vector<double>& crown,
                              const std::vector<ArchCurve::Projection>& cell_st,
                              const ArchCurve& curve, double floor, double half_width_mm);

/// Typical mesio-distal width of the tooth at `position` (1-8) of `jaw`, mm.
double TypicalWidthMm(io::Jaw jaw, int position);

/// The teeth of one jaw from its crown profile along `curve`, right to left; empty with `why`
/// when no plausible arrangement exists or its boundaries are no valleys (the median tooth's
/// confidence below 0.2: a surface without crowns).
std::vector<ToothSpan> SegmentTeeth(const CrownProfile& profile, const ArchCurve& curve,
                                    io::Jaw jaw, std::string* why);

}  // namespace occlude::analysis
