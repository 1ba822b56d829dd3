// The global validation runs and their summaries (see validate_global.h).
#include "validate/validate_global.h"

#include <algorithm>
#include <memory>
#include <random>

#include "base/percentile.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "occlude/planner/global_search.h"
#include "occlude/planner/global_starts.h"
#include "session/case_analysis.h"
#include "session/clinical_judge.h"
#include "session/global_request.h"
#include "validate/validate_internal.h"

namespace occlude::app {
namespace {

constexpr int kGlobalProposals = 8;  // K proposals per search, for seat_rank

// What every global run shares.
struct GlobalSetup {
  const JawPair* jaws = nullptr;
  const ValidateOptions* options = nullptr;
  CaseAnalysis analysis;
  planner::JawArch lower_L, upper_U;
  collision::OracleOptions oracle_base;
  Eigen::Isometry3d X_ref = Eigen::Isometry3d::Identity();
  planner::Proposal seat;
  std::vector<Eigen::Vector3d> points_U;
  Eigen::Vector3d pivot_L = Eigen::Vector3d::Zero();
  std::vector<std::vector<planner::PoseParameters>> near;
};

struct GlobalJob {
  std::size_t kind = 0;
  int start = 0;
  planner::SolverKind solver = planner::SolverKind::kCoarseToFine;
};

// The start pose of U in L; seeded per (kind, start), shared by all solvers.
Eigen::Isometry3d StartPose(const GlobalSetup& s, const GlobalJob& job) {
  if (GlobalStartKinds()[job.kind] == "near") {
    const std::size_t m = static_cast<std::size_t>(job.start) % s.near.size();
    return planner::ComposePose(s.near[m][static_cast<std::size_t>(job.start)], s.pivot_L, s.X_ref);
  }
  std::mt19937 rng(s.options->seed * 7919u + static_cast<std::uint32_t>(job.start) * 104729u +
                   static_cast<std::uint32_t>(job.kind) * 15485863u);
  const std::string& kind = GlobalStartKinds()[job.kind];
  if (kind == "sagittal")
    return planner::SagittalStart(s.X_ref, s.pivot_L, s.lower_L.anterior_J, rng);
  if (kind == "cusp") {
    const double shift_mm = (job.start % 2 == 0 ? 1.0 : -1.0) * s.options->cusp_period_mm;
    return planner::CuspStart(s.X_ref, s.pivot_L, s.lower_L.anterior_J, shift_mm, rng);
  }
  return planner::ApartStart(s.X_ref, s.pivot_L, rng);
}

// An arch in the frame J' = X J.
planner::JawArch Moved(planner::JawArch a, const Eigen::Isometry3d& X) {
  a.origin_J = X * a.origin_J;
  a.occlusal_J = X.linear() * a.occlusal_J;
  a.anterior_J = X.linear() * a.anterior_J;
  a.lateral_J = X.linear() * a.lateral_J;
  for (Eigen::Vector3d& p : a.curve_J) p = X * p;
  return a;
}

std::string ClassPair(const analysis::SideRelationship (&sides)[2]) {
  const auto one = [](const analysis::SideRelationship& side) {
    return side.occlusion_class ? std::string(analysis::ToString(*side.occlusion_class)) : "?";
  };
  return one(sides[0]) + "/" + one(sides[1]);
}

// The top proposal's relationships against the targets of the options.
void JudgeTop(const Eigen::Isometry3d& X_LU, const GlobalSetup& s, GlobalValidateRun* out) {
  const analysis::Relationships r = RelationshipsAt(s.analysis, X_LU);
  out->top_molar_class = ClassPair(r.molar);
  out->top_canine_class = ClassPair(r.canine);
  const std::vector<TargetCheck> checks = CheckTargets(s.options->clinical, r);
  out->targets_met = std::all_of(checks.begin(), checks.end(),
                                 [](const TargetCheck& c) { return !c.has_value || c.met; });
  out->top_penalty = JudgeRelationships(s.options->clinical, r).penalty;
}

// Fills the seat columns from the proposals (poses of U in L).
void ScoreSeat(const planner::GlobalResult& r, const Eigen::Isometry3d& X_start,
               const GlobalSetup& s, GlobalValidateRun* out) {
  const double bar_mm = s.options->success_mm, bar_deg = s.options->success_deg;
  for (std::size_t k = 0; k < r.proposals.size(); ++k) {
    const planner::PoseError e =
        planner::ComparePoses(r.proposals[k].proposal.X_LU * X_start, s.seat.X_LU, s.points_U);
    if (k == 0) out->seat_err_mm = e.translation_mm, out->seat_err_deg = e.rotation_deg;
    if (out->seat_rank == 0 && e.translation_mm <= bar_mm && e.rotation_deg <= bar_deg)
      out->seat_rank = static_cast<int>(k) + 1;
  }
  out->seat_success = out->seat_rank == 1;
}

void FillRun(const planner::GlobalResult& r, const Eigen::Isometry3d& X_start, const GlobalSetup& s,
             ValidateRun* run) {
  run->start_error = planner::ComparePoses(X_start, s.X_ref, s.points_U);
  run->seconds = r.cpu_seconds;
  run->evaluations = r.total_evaluations;
  if (r.proposals.empty()) {
    run->status = "no seat";
    run->error = {1e9, 180.0};
    return;
  }
  const planner::Proposal& best = r.proposals.front().proposal;
  run->X_LU = best.X_LU * X_start;
  run->error = planner::ComparePoses(run->X_LU, s.X_ref, s.points_U);
  run->found = planner::DecomposePose(run->X_LU, s.pivot_L, s.X_ref);
  run->max_penetration_mm = best.evaluation.max_penetration_mm;
  run->constrained_penetration_mm = best.evaluation.constrained_penetration_mm;
  run->contact_area_mm2 = best.evaluation.contact_area_mm2;
  run->contact_samples = best.evaluation.contact_samples;
  run->outliers = best.evaluation.outliers.size();
  run->status = planner::ToString(best.status);
  run->success = run->error.translation_mm <= s.options->success_mm &&
                 run->error.rotation_deg <= s.options->success_deg;
}

// One solver in global scope from one start: the upper mesh moved there, its oracles rebuilt.
GlobalValidateRun RunGlobalJob(const GlobalJob& job, const GlobalSetup& s) {
  const ValidateOptions& o = *s.options;
  const Eigen::Isometry3d X_start = StartPose(s, job);
  auto upper = std::make_shared<io::TriangleMesh>(s.jaws->upper_U->Transformed(X_start));
  const planner::OwnedSchedule schedule =
      planner::BuildSchedule(s.jaws->lower_L, upper, o.voxels_mm, o.exact_last, s.oracle_base);
  planner::GlobalRequest g;
  g.lower_L = s.lower_L;
  g.upper_U = Moved(s.upper_U, X_start);
  g.scan = o.global_scan;
  g.local = BaseRequest(o);
  g.local.solver = job.solver;
  g.local.max_proposals = kGlobalProposals;
  const ClinicalTargets& targets = o.clinical;
  const CaseAnalysis& analysis = s.analysis;
  g.ranking.judge = [&targets, &analysis, &X_start](const planner::GlobalProposal& seat) {
    return JudgeRelationships(targets, RelationshipsAt(analysis, seat.proposal.X_LU * X_start));
  };
  const planner::GlobalResult r = planner::GlobalSearch(schedule.stages, g);
  GlobalValidateRun out;
  out.start_kind = GlobalStartKinds()[job.kind];
  out.run.solver = job.solver;
  out.run.start = job.start;
  if (out.start_kind == "near")
    out.run.magnitude = o.magnitudes[static_cast<std::size_t>(job.start) % o.magnitudes.size()];
  out.proposals = static_cast<int>(r.proposals.size());
  out.excluded = static_cast<int>(r.excluded.size());
  out.wall_seconds = r.wall_seconds;
  FillRun(r, X_start, s, &out.run);
  ScoreSeat(r, X_start, s, &out);
  if (!r.proposals.empty()) JudgeTop(out.run.X_LU, s, &out);
  return out;
}

GlobalValidateSummary SummarizeKind(const std::vector<const GlobalValidateRun*>& group) {
  GlobalValidateSummary row;
  row.start_kind = group.front()->start_kind;
  row.solver = group.front()->run.solver;
  row.runs = static_cast<int>(group.size());
  std::vector<double> seat_mm, seat_deg, err_mm, cpu, wall;
  int ok = 0, seat_ok = 0, among = 0, met = 0;
  for (const GlobalValidateRun* r : group) {
    ok += r->run.success ? 1 : 0;
    met += r->targets_met ? 1 : 0;
    seat_ok += r->seat_success ? 1 : 0;
    among += r->seat_rank > 0 ? 1 : 0;
    seat_mm.push_back(r->seat_err_mm);
    seat_deg.push_back(r->seat_err_deg);
    err_mm.push_back(r->run.error.translation_mm);
    cpu.push_back(r->run.seconds);
    wall.push_back(r->wall_seconds);
    row.max_seconds = std::max(row.max_seconds, r->run.seconds);
    row.worst_penetration_mm =
        std::max(row.worst_penetration_mm, r->run.constrained_penetration_mm);
  }
  const double n = static_cast<double>(group.size());
  row.success_rate = ok / n;
  row.seat_success_rate = seat_ok / n;
  row.seat_among_rate = among / n;
  row.targets_met_rate = met / n;
  row.median_seat_err_mm = NearestRankPercentile(seat_mm, 0.5, 0.0);
  row.p95_seat_err_mm = NearestRankPercentile(seat_mm, 0.95, 0.0);
  row.median_seat_err_deg = NearestRankPercentile(seat_deg, 0.5, 0.0);
  row.median_err_mm = NearestRankPercentile(err_mm, 0.5, 0.0);
  row.median_seconds = NearestRankPercentile(cpu, 0.5, 0.0);
  row.median_wall_seconds = NearestRankPercentile(wall, 0.5, 0.0);
  return row;
}

// The indices in GlobalStartKinds() of the kinds asked for, in its order; a UserError naming
// --kinds for an unknown kind or none.
std::vector<std::size_t> KindIndices(const std::vector<std::string>& asked) {
  const std::vector<std::string>& all = GlobalStartKinds();
  std::string names;
  for (const std::string& kind : all) names += (names.empty() ? "" : ", ") + kind;
  for (const std::string& kind : asked) {
    if (std::find(all.begin(), all.end(), kind) == all.end())
      throw UserError("--kinds: '" + kind + "' is not a start kind; use " + names);
  }
  std::vector<std::size_t> indices;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (std::find(asked.begin(), asked.end(), all[k]) != asked.end()) indices.push_back(k);
  }
  if (indices.empty()) throw UserError("--kinds: give at least one of " + names);
  return indices;
}

// The seat of the reference: the best seat the local search reaches from the reference, as the
// closing run of `validate --magnitudes 0:0` searches (coarse-to-fine with its internal starts,
// within the bound margins of the reference; the reference itself is one of the starts),
// polished as the global search polishes its seats.
// A single local search from the reference can stall on a poor seat (c4-ios: 0.57 mm^2 of
// contact where its internal starts find 23 mm^2 within 0.3 mm).
planner::Proposal SeatOfReference(const planner::OracleSchedule& stages,
                                  const Eigen::Isometry3d& X_ref, const ValidateOptions& o) {
  planner::PlanRequest r =
      BoundedRequest(o, Magnitude{}, planner::SolverKind::kCoarseToFine, X_ref);
  r.seed = o.seed;
  r.polish = true;  // as the global search refines its seats
  return planner::Plan(stages, r).proposals.front();
}

// The arches, the seat of the reference and the shared settings.
void Prepare(const JawPair& jaws, const ValidateOptions& options, GlobalSetup* s) {
  s->jaws = &jaws;
  s->options = &options;
  s->X_ref = jaws.X_LU_ref;
  s->analysis = AnalyzeCase(jaws);
  s->lower_L = JawArchOf(s->analysis.lower_L, jaws.name);
  s->upper_U = JawArchOf(s->analysis.upper_U, jaws.name);
  s->oracle_base.arch = planner::FrameOf(s->lower_L);
  s->near = Perturbations(options);
}

}  // namespace

const std::vector<std::string>& GlobalStartKinds() {
  static const std::vector<std::string> kinds = {"near", "sagittal", "apart", "cusp"};
  return kinds;
}

GlobalValidateResult RunGlobalValidation(const JawPair& jaws, const ValidateOptions& options) {
  const std::vector<std::size_t> kinds = KindIndices(options.global_kinds);
  GlobalValidateResult result;
  result.case_name = jaws.name;
  GlobalSetup s;
  const double t0 = NowSeconds();
  Prepare(jaws, options, &s);
  const planner::OwnedSchedule schedule = planner::BuildSchedule(
      jaws.lower_L, jaws.upper_U, options.voxels_mm, options.exact_last, s.oracle_base);
  result.build_seconds = NowSeconds() - t0;
  s.points_U = planner::ArchReferencePoints_U(*jaws.upper_U, s.X_ref, *s.oracle_base.arch);
  s.pivot_L = s.X_ref * s.points_U[0];
  s.seat = SeatOfReference(schedule.stages, s.X_ref, options);
  result.seat = s.seat;
  result.seat_from_reference = planner::ComparePoses(s.seat.X_LU, s.X_ref, s.points_U);
  std::vector<GlobalJob> jobs;
  for (const std::size_t kind : kinds) {
    for (int k = 0; k < options.starts; ++k) {
      for (const planner::SolverKind solver : options.solvers) jobs.push_back({kind, k, solver});
    }
  }
  result.runs.resize(jobs.size());
  RunInParallel(jobs.size(), options,
                [&](std::size_t j) { result.runs[j] = RunGlobalJob(jobs[j], s); });
  for (const std::size_t kind : kinds) {
    for (const planner::SolverKind solver : options.solvers) {
      std::vector<const GlobalValidateRun*> group;
      for (const GlobalValidateRun& r : result.runs) {
        if (r.start_kind == GlobalStartKinds()[kind] && r.run.solver == solver) group.push_back(&r);
      }
      if (!group.empty()) result.summary.push_back(SummarizeKind(group));
    }
  }
  return result;
}

}  // namespace occlude::app
