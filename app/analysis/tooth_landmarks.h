// The landmarks of ../shared/docs/clinical.md on one tooth, found geometrically in its tooth
// view: cusp tips as the middle of the plateau of the highest local maximum of the occlusal
// surface (its height above the plane of the crown's occlusal table: crowns are inclined) in each
// cusp's region of the crown (mesial / distal halves or thirds, buccal / lingual halves), a
// canine's tip as the middle of the highest cells of its region mesial of the crown's middle
// (along the arch, then across the slice there: a worn tip is flat), the incisal edge's middle
// as the middle of its ridge's highest cells, the central fossa as the middle of the lowest
// points of the crown's middle (its floor), contact points at the crown's mesial and distal ends
// (between two whole crowns: their closest points, PlaceContacts), and facial / lingual points
// where the crown's surface triangles cross its middle on each side (on the line across square
// to the row of teeth, ToothView::arch_slope), halfway down the clinical crown from that side's
// top. A cusp whose region holds no local maximum is left out, except those a relationship rests
// on (buccal and mesiobuccal / middle buccal cusps): they take the region's highest cell,
// confidence 0.4.
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
