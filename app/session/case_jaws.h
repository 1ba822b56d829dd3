// A case's jaws as the report (and later propose/refine) use them: the meshes
// named by a CaseConfig loaded with user-facing errors, the arch frame (from the
// up-axis hint or estimated) and the default rotation pivot.
//
// Frames: both meshes are returned as given: lower in L, upper in U, where U is
// the frame the upper mesh came in (for the synthetic pair the upper is moved to
// L at its ground-truth bite, like `occlude synth` case folders), so X_LU =
// identity is the pose "as scanned".
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "config/case_config.h"
#include "occlude/collision/oracle.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

struct CaseJaws {
  std::shared_ptr<const io::TriangleMesh> lower_L;
  std::shared_ptr<const io::TriangleMesh> upper_U;
  /// Synthetic pair only: the known contact points at X_LU = identity.
  std::vector<Eigen::Vector3d> truth_contacts_L;
};

/// Loads the meshes (files, part files or the synthetic pair). Throws UserError
/// naming the file; mesh warnings go to stderr.
CaseJaws LoadCaseJaws(const CaseConfig& config);

/// Arch frame for shares and views: EstimateArchFrame on the jaws at X_LU; with
/// an up-axis hint the occlusal axis is the hint and the anterior direction the
/// estimate's, made perpendicular.
collision::ArchFrame CaseArchFrame(const CaseConfig& config, const io::TriangleMesh& lower_L,
                                   const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU);

}  // namespace occlude::app
