// The landmarks of ../shared/docs/clinical.md on one tooth, found geometrically in its tooth
// view: cusp tips as the highest local maxima of the occlusal surface in each cusp's region of
// the crown (mesial / distal halves or thirds, buccal / lingual halves), the incisal edge's
// middle as the highest point of the middle slice, the central fossa as the lowest point of the
// crown's middle, contact points at the crown's mesial and distal ends, and facial / lingual
// points on the outer surfaces of the middle slice halfway down the clinical crown. A landmark
// whose region holds no local maximum is left out.
#pragma once

#include <vector>

#include "arch_analysis.h"
#include "tooth_view.h"

namespace occlude::analysis {

/// Typical anatomical crown height of the tooth at `position` (1-8) of `jaw` (Wheeler), mm.
double TypicalCrownHeightMm(io::Jaw jaw, int position);

/// Landmarks found on the tooth (points in J, source kDetected); `tooth_confidence` scales
/// their confidences.
std::vector<ArchLandmark> DetectToothLandmarks(const ToothView& view, double tooth_confidence);

/// Between two neighbouring whole crowns (parts or shells; `a` right of `b` along the arch), the
/// contact points are where they come closest: replaces a's and b's facing mesial / distal
/// landmarks in `landmarks` by the closest pair of their vertices near those ends. Does nothing
/// unless both views are whole crowns.
void PlaceContacts(const ToothView& a, const ToothView& b, double tooth_confidence,
                   std::vector<ArchLandmark>* landmarks);

}  // namespace occlude::analysis
