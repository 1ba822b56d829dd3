// Shared fixture of the planner tests: the smallest synthetic jaw pair with a
// coarse schedule (built once per test program), and a perturbed start. Each
// ctest test is a process of its own, so what only some tests need (the coarse
// stage of coarse-to-fine) is built on first use: under the sanitizers an
// oracle build costs seconds.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "occlude/io/synthetic_jaws.h"
#include "occlude/planner/plan.h"

namespace occlude::planner::test {

struct SyntheticCase {
  io::SyntheticJawPair pair;
  std::shared_ptr<const io::TriangleMesh> lower, upper;
  OwnedSchedule schedule;  ///< 0.5 mm subvoxel (coarser blurs the locking inclines)
  std::vector<Eigen::Vector3d> points_U;
  Eigen::Vector3d pivot_L;
};

inline const SyntheticCase& Synthetic() {
  static const SyntheticCase* c = [] {
    auto* s = new SyntheticCase;
    io::SyntheticJawOptions o;
    o.triangles_per_jaw = io::kMinSyntheticTriangles;
    s->pair = io::MakeSyntheticJawPair(o);
    s->lower = std::make_shared<io::TriangleMesh>(s->pair.lower_L);
    s->upper = std::make_shared<io::TriangleMesh>(s->pair.upper_U);
    s->schedule = BuildSchedule(s->lower, s->upper, {0.5}, false);
    const auto& arch = s->schedule.stages.back().oracle->arch();
    s->points_U = ArchReferencePoints_U(*s->upper, s->pair.X_LU, arch);
    s->pivot_L = s->pair.X_LU * s->points_U[0];
    return s;
  }();
  return *c;
}

/// Coarse to fine: 0.8 mm then 0.5 mm subvoxel (BuildSchedule's stages; the 0.5 mm oracle is
/// the one of Synthetic().schedule, built with the same options).
inline const OracleSchedule& CoarseToFine() {
  static const OracleSchedule* stages = [] {
    const SyntheticCase& c = Synthetic();
    static const collision::JawOracle coarse(c.lower, c.upper,
                                             StageOracleOptions({}, {0.8, 0.5}, 0));
    return new OracleSchedule{{&coarse, collision::AccuracyLevel::kSubVoxel},
                              c.schedule.stages.back()};
  }();
  return *stages;
}

/// A request starting from the ground truth perturbed by t_mm / r_deg along fixed directions.
inline PlanRequest PerturbedRequest(SolverKind solver, double t_mm, double r_deg, int variant = 0) {
  const SyntheticCase& c = Synthetic();
  PoseParameters perturb;
  const Eigen::Vector3d dirs[3] = {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(-1, 0.5, 1),
                                   Eigen::Vector3d(0.3, -1, -1)};
  perturb.translation_mm = t_mm * dirs[variant % 3].normalized();
  perturb.rotation_deg = r_deg * dirs[(variant + 1) % 3].normalized();
  PlanRequest req;
  req.solver = solver;
  req.X_LU_start = ComposePose(perturb, c.pivot_L, c.pair.X_LU);
  req.num_starts = 1;
  req.num_threads = 1;
  req.num_global_samples = 8;
  req.max_proposals = 1;
  return req;
}

}  // namespace occlude::planner::test
