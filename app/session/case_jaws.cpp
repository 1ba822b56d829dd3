// Loading a case's jaws and its arch frame (see report_case.h).
#include "session/case_jaws.h"

#include <algorithm>
#include <iostream>

#include "base/user_error.h"
#include "occlude/io/mesh_io.h"
#include "session/synthetic_case.h"

namespace occlude::app {
namespace {

io::TriangleMesh LoadJaw(const JawFiles& jaw, const CaseConfig& config) {
  io::LoadOptions options;
  options.unit = config.units;
  io::LoadReport report;
  try {
    io::TriangleMesh mesh = jaw.parts ? io::LoadJawParts(jaw.files, options, &report)
                                      : io::LoadMesh(jaw.files.front(), options, &report);
    for (const auto& w : report.warnings) std::cerr << "occlude: warning: " << w << "\n";
    return mesh;
  } catch (const io::MeshError& e) {
    throw UserError(e.what());
  }
}

}  // namespace

CaseJaws LoadCaseJaws(const CaseConfig& config) {
  CaseJaws jaws;
  if (config.synthetic) {
    io::SyntheticJawOptions options;
    options.triangles_per_jaw = config.synthetic->triangles;
    options.seed = config.synthetic->seed;
    const io::SyntheticJawPair pair = MakeSyntheticOrExplain(options);
    jaws.lower_L = std::make_shared<io::TriangleMesh>(pair.lower_L);
    jaws.upper_U = std::make_shared<io::TriangleMesh>(pair.upper_U.Transformed(pair.X_LU));
    for (const auto& c : pair.contacts) jaws.truth_contacts_L.push_back(c.p_L);
    return jaws;
  }
  jaws.lower_L = std::make_shared<io::TriangleMesh>(LoadJaw(*config.lower, config));
  jaws.upper_U = std::make_shared<io::TriangleMesh>(LoadJaw(*config.upper, config));
  return jaws;
}

collision::ArchFrame CaseArchFrame(const CaseConfig& config, const io::TriangleMesh& lower_L,
                                   const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU) {
  collision::ArchFrame f = collision::EstimateArchFrame(lower_L, upper_U.Transformed(X_LU));
  if (!config.up_axis_L) return f;
  const Eigen::Vector3d up = *config.up_axis_L;
  Eigen::Vector3d anterior = f.anterior_L - f.anterior_L.dot(up) * up;
  if (anterior.norm() < 1e-6) anterior = up.unitOrthogonal();
  f.occlusal_L = up;
  f.anterior_L = anterior.normalized();
  f.lateral_L = f.occlusal_L.cross(f.anterior_L).normalized();
  return f;
}

}  // namespace occlude::app
