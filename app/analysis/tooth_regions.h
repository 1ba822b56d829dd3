// Which surface belongs to which tooth: mesh parts carrying tooth numbers (3Shape part files,
// the synthetic pair), else separate shells numbered along the arch from the midline, else
// spans of the arch curve cut out of a single surface (tooth_segmentation.h), each between the
// cuts along the valleys to its neighbours (tooth_cut.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "arch_analysis.h"
#include "arch_geometry.h"
#include "tooth_cut.h"

namespace occlude::analysis {

struct ToothRegion {
  int fdi = 0;
  ToothSource source = ToothSource::kSegmented;
  std::vector<std::int32_t> triangles;  ///< parts and shells: the tooth's triangles
  double s_lo = 0.0, s_hi = 0.0;        ///< segmented: its span along the curve, mm
  ToothCut right_cut, left_cut;  ///< segmented: its cuts across the arch (s_lo, s_hi at t = 0)
  double confidence = 0.0;
};

/// The teeth of `mesh` (one jaw, `jaw`), right to left; empty with `why` when none is found.
std::vector<ToothRegion> FindTeeth(const io::TriangleMesh& mesh, const ArchGeometry& g, io::Jaw jaw,
                                   std::vector<std::string>* notes, std::string* why);

/// Connected components of the mesh's triangles (through shared vertices), each a list of
/// triangle indices, in order of their first triangle.
std::vector<std::vector<std::int32_t>> Components(const io::TriangleMesh& mesh);

}  // namespace occlude::analysis
