// The landscape between a registered bite and another pose: evaluates the poses on the straight
// path (in the pivot parameters) from the pose as given (s = 0) to the pose
// (tx ty tz mm, rx ry rz deg about the occlusal pivot) at s = 1 and beyond, each as is and
// settled along the occlusal axis until the outlier-robust penetration meets the limit. Tells
// whether the registered pose is a local optimum of "maximal contact, no interpenetration"
// (contact that keeps growing along a feasible path says it is not).
//   occlude_bite_path <case folder> tx ty tz rx ry rz [voxel_mm=0.2] [steps=10] [s_max=1.2]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "occlude/planner/evaluation.h"
#include "occlude/planner/plan.h"
#include "session/jaw_pair.h"

using namespace occlude;

int main(int argc, char** argv) {
  if (argc < 8) {
    std::fprintf(stderr, "usage: %s <case folder> tx ty tz rx ry rz [voxel_mm] [steps] [s_max]\n",
                 argv[0]);
    return 2;
  }
  const std::string dir = argv[1];
  planner::PoseParameters target;
  target.translation_mm = {std::atof(argv[2]), std::atof(argv[3]), std::atof(argv[4])};
  target.rotation_deg = {std::atof(argv[5]), std::atof(argv[6]), std::atof(argv[7])};
  const double voxel = argc > 8 ? std::atof(argv[8]) : 0.2;
  const int steps = argc > 9 ? std::atoi(argv[9]) : 10;
  const double s_max = argc > 10 ? std::atof(argv[10]) : 1.2;

  try {
    const app::JawPair jaws = app::LoadCaseFolder(dir);
    const auto& lower = jaws.lower_L;
    const auto& upper = jaws.upper_U;
    const planner::OwnedSchedule schedule = planner::BuildSchedule(lower, upper, {voxel}, false);
    const planner::OracleStage& stage = schedule.stages.back();
    const auto& arch = stage.oracle->arch();
    const Eigen::Isometry3d X_ref = Eigen::Isometry3d::Identity();
    const auto points_U = planner::ArchReferencePoints_U(*upper, X_ref, arch);
    const Eigen::Vector3d pivot_L = X_ref * points_U[0];
    const planner::PlanRequest
        request;  // defaults: band, penetration limit and measure of `propose`
    std::printf("case %s, voxel %.2f mm sub-voxel, band %.2f mm, limit %.3f mm (robust measure)\n",
                dir.c_str(), voxel, request.contact_band_mm, request.max_penetration_mm);
    std::printf("pivot_L (%.3f %.3f %.3f), occlusal_L (%.3f %.3f %.3f)\n", pivot_L.x(), pivot_L.y(),
                pivot_L.z(), arch.occlusal_L.x(), arch.occlusal_L.y(), arch.occlusal_L.z());
    std::printf(
        "    s  err_mm err_deg | as is: contact  post%%  maxpen  robust | settled: shift_mm "
        "contact  post%%  maxpen  robust\n");
    // The path to s_max: the pivot parameters scale linearly along EvaluatePath's path.
    planner::PoseParameters end;
    end.translation_mm = s_max * target.translation_mm;
    end.rotation_deg = s_max * target.rotation_deg;
    const std::vector<planner::PathPoint> path =
        planner::EvaluatePath(stage, X_ref, planner::ComposePose(end, pivot_L, X_ref), pivot_L,
                              points_U, request, std::max(1, steps));
    for (const planner::PathPoint& point : path) {
      const double s = s_max * point.s;
      const Eigen::Isometry3d& X = point.X_LU;
      const planner::PoseError& e = point.from_start;
      const planner::PoseEvaluation& as_is = point.evaluation;
      // Settle: the largest shift along the closing direction (-occlusal: upper toward lower)
      // that keeps the robust measure within the limit (bisection; 0.01 um). The planner's own
      // settle (detail::SettleOnOracle) is internal to the library and moves the pivot
      // parameters; this one is a pure translation, so that the column reads in mm.
      auto shifted = [&](double c) {
        Eigen::Isometry3d Y = X;
        Y.pretranslate(-c * arch.occlusal_L);
        return Y;
      };
      auto ok = [&](double c) {
        return planner::EvaluatePose(stage, shifted(c), request).feasible;
      };
      double lo = -1.0, hi = 1.0;  // lo feasible (open), hi infeasible
      while (!ok(lo) && lo > -4.0) lo -= 1.0;
      while (ok(hi) && hi < 4.0) hi += 1.0;
      for (int it = 0; it < 40; ++it) {
        const double mid = 0.5 * (lo + hi);
        (ok(mid) ? lo : hi) = mid;
      }
      const planner::PoseEvaluation settled = planner::EvaluatePose(stage, shifted(lo), request);
      std::printf(
          "%5.2f  %6.3f %7.3f | %13.2f %6.1f %7.3f %7.3f | %16.3f %7.2f %6.1f %7.3f %7.3f\n", s,
          e.translation_mm, e.rotation_deg, as_is.contact_area_mm2, 100.0 * as_is.posterior_share,
          as_is.max_penetration_mm, as_is.constrained_penetration_mm, lo, settled.contact_area_mm2,
          100.0 * settled.posterior_share, settled.max_penetration_mm,
          settled.constrained_penetration_mm);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
