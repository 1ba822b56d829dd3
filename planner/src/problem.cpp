// The search problem as a 6-vector x = (translation mm, rotation deg) relative
// to the start pose about the pivot: pose conversion, bounds, locks and the
// settle direction.
#include <cmath>
#include <stdexcept>

#include "occlude/collision/arch_frame.h"
#include "search_internal.h"

namespace occlude::planner::detail {

PoseParameters ToParameters(const Vector6d& x) {
  PoseParameters p;
  p.translation_mm = x.head<3>();
  p.rotation_deg = x.tail<3>();
  return p;
}

Vector6d FromParameters(const PoseParameters& p) {
  Vector6d x;
  x << p.translation_mm, p.rotation_deg;
  return x;
}

bool Finite(const Vector6d& x) { return x.allFinite(); }

Eigen::Isometry3d PoseOf(const Problem& problem, const Vector6d& x) {
  return ComposePose(ToParameters(x), problem.pivot_L, problem.X_ref);
}

Vector6d ParamsOf(const Problem& problem, const Eigen::Isometry3d& X_LU) {
  return FromParameters(DecomposePose(X_LU, problem.pivot_L, problem.X_ref));
}

Vector6d Clamp(const Problem& problem, const Vector6d& x) {
  return x.cwiseMax(problem.lower).cwiseMin(problem.upper);
}

Problem MakeProblem(const OracleSchedule& schedule, const PlanRequest& request,
                    const collision::ArchFrame* arch) {
  ValidateRequest(request);
  if (schedule.empty())
    throw std::invalid_argument("schedule: empty; give at least one OracleStage");
  for (const OracleStage& s : schedule) {
    if (s.oracle == nullptr) throw std::invalid_argument("schedule: an OracleStage has no oracle");
  }
  const collision::JawOracle& finest = *schedule.back().oracle;
  Problem p;
  p.request = &request;
  p.X_ref = request.X_LU_start;
  p.arch = arch ? *arch : finest.arch();
  const io::TriangleMesh& upper_U = finest.upper_tree().mesh();
  p.pivot_L = request.pivot_L ? *request.pivot_L
                              : collision::UpperOcclusalCentre(upper_U, p.X_ref, p.arch.occlusal_L);
  p.lower << request.lower_bound.translation_mm, request.lower_bound.rotation_deg;
  p.upper << request.upper_bound.translation_mm, request.upper_bound.rotation_deg;
  for (int i = 0; i < kNumDof; ++i) {
    if (request.locked[static_cast<std::size_t>(i)]) p.lower[i] = p.upper[i] = 0.0;
  }
  p.settle_dir = p.arch.occlusal_L;
  for (int i = 0; i < 3; ++i) {
    if (request.locked[static_cast<std::size_t>(i)]) p.settle_dir[i] = 0.0;
  }
  if (p.settle_dir.norm() > 1e-6) {
    p.settle_dir.normalize();
  } else {
    p.settle_dir.setZero();
  }
  p.ref_points_U = ArchReferencePoints_U(upper_U, p.X_ref, p.arch);
  return p;
}

}  // namespace occlude::planner::detail
