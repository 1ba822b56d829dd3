// Synthetic viewer inputs (see viewer_fixture.h).
#include "viewer_fixture.h"

#include "occlude/angles.h"
#include "occlude/collision/oracle.h"
#include "occlude/collision/signed_distance.h"
#include "occlude/io/synthetic_jaws.h"

namespace occlude::test {

using app::ViewerInputs;
using app::ViewerProposal;

std::vector<float> BruteForceDistances(const io::TriangleMesh& mesh_F,
                                       const Eigen::Isometry3d& X_GF,
                                       const io::TriangleMesh& other_G) {
  const collision::PseudoNormals normals(other_G);
  std::vector<float> out;
  out.reserve(mesh_F.num_vertices());
  for (const Eigen::Vector3d& p_F : mesh_F.vertices) {
    collision::SignedDistanceSample s;
    collision::SignedDistanceBruteForce(other_G, normals, X_GF * p_F, &s);
    out.push_back(static_cast<float>(s.distance));
  }
  return out;
}

std::unique_ptr<ViewerFixture> MakeSyntheticViewer(int proposals, std::size_t triangles) {
  const io::SyntheticJawPair pair = io::MakeSyntheticJawPair({20000, 1});
  auto f = std::make_unique<ViewerFixture>();
  f->lower = io::DecimateForDisplay(pair.lower_L, {triangles});
  f->upper = io::DecimateForDisplay(pair.upper_U, {triangles});
  ViewerInputs& in = f->inputs;
  in.lower_L = &f->lower.mesh;
  in.upper_U = &f->upper.mesh;
  const collision::ArchFrame arch =
      collision::EstimateArchFrame(pair.lower_L, pair.upper_U.Transformed(pair.X_LU));
  in.axes = {arch.occlusal_L, arch.anterior_L, arch.lateral_L};
  in.title = "Synthetic jaws";
  const Eigen::Vector3d occlusal = pair.occlusal_axis_L;
  Eigen::Isometry3d opened = Eigen::Translation3d(0.3 * occlusal) *
                             Eigen::AngleAxisd(RadiansFromDegrees(3.0), occlusal) * pair.X_LU;
  Eigen::Isometry3d pushed = Eigen::Translation3d(-0.15 * occlusal) * pair.X_LU;
  const Eigen::Isometry3d poses[] = {pair.X_LU, opened, pushed};
  const char* numbers[] = {"{\"contact area (mm\u00b2)\": 12.5, \"status\": \"converged\"}",
                           "{\"contact area (mm\u00b2)\": 0, \"opening (mm)\": 0.3}",
                           "{\"contact area (mm\u00b2)\": 30.1, \"max penetration (mm)\": 0.15}"};
  for (int i = 0; i < proposals; ++i) {
    ViewerProposal p;
    p.label = "proposal " + std::to_string(i + 1);
    p.X_LU = poses[i];
    p.numbers_json = numbers[i];
    p.lower_distance_mm = BruteForceDistances(f->lower.mesh, Eigen::Isometry3d::Identity(),
                                              f->upper.mesh.Transformed(p.X_LU));
    p.upper_distance_mm = BruteForceDistances(f->upper.mesh, p.X_LU, f->lower.mesh);
    in.proposals.push_back(std::move(p));
  }
  return f;
}

}  // namespace occlude::test
