// Viewer inputs for the tests: the synthetic jaw pair decimated for display, with
// exact signed distances (brute force against the opposing display mesh) at the
// designed bite and at poses opened and turned from it.
#pragma once

#include <memory>
#include <string>

#include "occlude/io/display_decimation.h"
#include "viewer/viewer_page.h"

namespace occlude::test {

struct ViewerFixture {
  io::DecimationResult lower;  ///< display lower jaw, L
  io::DecimationResult upper;  ///< display upper jaw, U
  app::ViewerInputs inputs;    ///< points at lower.mesh and upper.mesh
};

/// `proposals` poses (1..3): the bite, then 0.3 mm open and turned 3 deg about the
/// occlusal axis, then 0.15 mm pushed in (penetrating). `triangles` per display jaw.
std::unique_ptr<ViewerFixture> MakeSyntheticViewer(int proposals, std::size_t triangles = 6000);

/// Per vertex of `mesh_F` placed by X_GF: the signed distance (mm) to `other_G`, brute force.
std::vector<float> BruteForceDistances(const io::TriangleMesh& mesh_F,
                                       const Eigen::Isometry3d& X_GF,
                                       const io::TriangleMesh& other_G);

}  // namespace occlude::test
