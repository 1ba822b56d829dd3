// The validation starts of the global search (see global_starts.h).
#include "occlude/planner/global_starts.h"

#include <cmath>

#include "occlude/planner/pose.h"

namespace occlude::planner {

Eigen::Vector3d RandomUnitVector(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  return Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
}

Eigen::Matrix3d UniformRotation(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

Eigen::Isometry3d SagittalStart(const Eigen::Isometry3d& X_LU_ref, const Eigen::Vector3d& p_LPivot,
                                const Eigen::Vector3d& anterior_L, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double shift = (3.0 + 9.0 * unit(rng)) * (unit(rng) < 0.5 ? -1.0 : 1.0);
  PoseParameters p;
  p.translation_mm = shift * anterior_L;
  p.rotation_deg = 10.0 * unit(rng) * RandomUnitVector(rng);
  return ComposePose(p, p_LPivot, X_LU_ref);
}

Eigen::Isometry3d CuspStart(const Eigen::Isometry3d& X_LU_ref, const Eigen::Vector3d& p_LPivot,
                            const Eigen::Vector3d& anterior_L, double shift_mm, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  PoseParameters p;
  p.translation_mm = shift_mm * anterior_L + 0.5 * std::cbrt(unit(rng)) * RandomUnitVector(rng);
  p.rotation_deg = 3.0 * unit(rng) * RandomUnitVector(rng);
  return ComposePose(p, p_LPivot, X_LU_ref);
}

Eigen::Isometry3d ApartStart(const Eigen::Isometry3d& X_LU_ref, const Eigen::Vector3d& p_LPivot,
                             std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Isometry3d turn = Eigen::Translation3d(p_LPivot) *
                                 Eigen::Isometry3d(UniformRotation(rng)) *
                                 Eigen::Translation3d(-p_LPivot);
  return Eigen::Translation3d((20.0 + 40.0 * unit(rng)) * RandomUnitVector(rng)) * turn * X_LU_ref;
}

}  // namespace occlude::planner
