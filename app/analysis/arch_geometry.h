// The geometry every tooth detection of one jaw reads: its occlusal plane, its arch axes
// (lateral to the patient's left, anterior, occlusal out of the crowns), the jaw seen from the
// occlusal side along them, and the arch curve fitted on that view.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "arch_analysis.h"
#include "arch_curve.h"
#include "height_map.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::analysis {

struct ArchGeometry {
  ViewAxes axes;    ///< e1 lateral, e2 anterior, up occlusal; origin on the occlusal plane
  HeightMap top;    ///< the whole jaw seen along `axes.up_J`
  ArchCurve curve;  ///< in `axes`' plane coordinates
  std::vector<ArchCurve::Projection> cell_st;
  std::vector<ArchCurve::Projection>
      vertex_st;  ///< per mesh vertex: its (s, t)  ///< per cell of `top`: its (s, t) on the curve
  double crown_floor = 0.0;   ///< crowns are the cells at least this high (plane at 0), mm
  std::vector<double> crown;  ///< per cell of `top`: its CrownWeights (0: not crown)
  double confidence = 0.0;    ///< of the orientation, in [0, 1]
};

/// The lateral direction (to the patient's left) of a jaw with the given occlusal and anterior
/// directions: for the lower jaw (occlusal up) occlusal x anterior, for the upper jaw (occlusal
/// anatomically down) anterior x occlusal.
Eigen::Vector3d PatientLeft(io::Jaw jaw, const Eigen::Vector3d& occlusal,
                            const Eigen::Vector3d& anterior);

/// Orientation, view and curve of `mesh` (non-empty). nullopt with `why` when no arch is found;
/// doubts go to `notes`.
std::optional<ArchGeometry> BuildArchGeometry(const io::TriangleMesh& mesh, io::Jaw jaw,
                                              const ArchAnalysisOptions& options,
                                              std::vector<std::string>* notes, std::string* why);

}  // namespace occlude::analysis
