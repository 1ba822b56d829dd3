// The global search's request of a case (see global_request.h).
#include "session/global_request.h"

#include <stdexcept>

#include "base/user_error.h"
#include "session/clinical_judge.h"

namespace occlude::app {

planner::JawArch JawArchOf(const analysis::ArchAnalysis& a, const std::string& source) {
  const std::string jaw = a.jaw == io::Jaw::kLower ? "lower" : "upper";
  if (!a.ok()) {
    throw UserError(source + ": the " + jaw + " jaw: " + a.error +
                    "; the global search needs the arch of both jaws (check the files, or give "
                    "solver.scope = \"local\" with a start pose)");
  }
  if (a.arch_curve_J.size() < 4) {
    throw UserError(source + ": the " + jaw +
                    " jaw: no arch curve found; the global search needs the arch of both jaws");
  }
  planner::JawArch arch;
  arch.occlusal_J = a.frame.occlusal_J;
  arch.anterior_J = a.frame.anterior_J;
  arch.lateral_J = a.frame.lateral_J;
  arch.origin_J =
      a.midline_J - (a.midline_J - a.frame.origin_J).dot(arch.occlusal_J) * arch.occlusal_J;
  arch.curve_J = a.arch_curve_J;
  return arch;
}

planner::GlobalRequest GlobalRequestFromConfig(const CaseConfig& config,
                                               const CaseAnalysis& analysis,
                                               const planner::PlanRequest& local) {
  planner::GlobalRequest g;
  g.lower_L = JawArchOf(analysis.lower_L, config.file.string());
  g.upper_U = JawArchOf(analysis.upper_U, config.file.string());
  g.local = local;
  const SolverSettings& solver = config.solver;
  if (solver.global_sagittal_step_mm) g.scan.sagittal_step_mm = *solver.global_sagittal_step_mm;
  if (solver.global_max_basins) g.scan.max_basins = *solver.global_max_basins;
  if (solver.global_max_refined) g.scan.max_refined = *solver.global_max_refined;
  g.ranking.judge = ClinicalJudge(config.clinical, analysis);
  try {
    planner::ValidateGlobalRequest(g);
  } catch (const std::invalid_argument& e) {
    throw UserError(config.file.string() +
                    ": the two arches cannot face each other for the global search (the same "
                    "jaw twice, or one mirrored or upside down?): " +
                    e.what());
  }
  return g;
}

}  // namespace occlude::app
