// The validation runs and their summaries (see validate.h).
#include "validate/validate.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <ostream>
#include <random>
#include <sstream>
#include <thread>

#include "base/percentile.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "validate/validate_internal.h"

namespace occlude::app {
namespace {

using planner::PoseError;
using planner::PoseParameters;
using planner::SolverKind;

// Uniform in the ball of `radius`: direction uniform on the sphere, length radius * u^(1/3).
Eigen::Vector3d InBall(std::mt19937& rng, double radius) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Vector3d d(g(rng), g(rng), g(rng));
  while (d.norm() < 1e-12) d = Eigen::Vector3d(g(rng), g(rng), g(rng));
  return radius * std::cbrt(u(rng)) * d.normalized();
}

// The medoid of `runs` (largest displacement of the reference points as the distance).
std::size_t Medoid(const std::vector<const ValidateRun*>& runs,
                   const std::vector<Eigen::Vector3d>& points_U) {
  std::size_t medoid = 0;
  double best_sum = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    double sum = 0.0;
    for (const ValidateRun* other : runs)
      sum += planner::ComparePoses(runs[i]->X_LU, other->X_LU, points_U).translation_mm;
    if (sum < best_sum) best_sum = sum, medoid = i;
  }
  return medoid;
}

ReferenceCheck CheckReference(const std::vector<ValidateRun>& runs,
                              const planner::OracleStage& stage, const Eigen::Isometry3d& X_ref,
                              const Eigen::Vector3d& pivot_L,
                              const std::vector<Eigen::Vector3d>& points_U,
                              const planner::PlanRequest& request, const ValidateOptions& options) {
  ReferenceCheck check;
  if (runs.empty()) return check;
  std::vector<const ValidateRun*> all;
  for (const ValidateRun& r : runs) all.push_back(&r);
  check.X_LU_consensus = all[Medoid(all, points_U)]->X_LU;
  check.consensus_error = planner::ComparePoses(check.X_LU_consensus, X_ref, points_U);
  check.path = planner::EvaluatePath(stage, X_ref, check.X_LU_consensus, pivot_L, points_U, request,
                                     std::max(1, options.path_steps));
  const planner::PoseEvaluation& reference = check.path.front().evaluation;
  for (std::size_t k = 1; k < check.path.size(); ++k) {
    const planner::PoseEvaluation& e = check.path[k].evaluation;
    if (!planner::Dominates(e, reference)) continue;
    const planner::PoseError& d = check.path[k].from_start;
    const bool beyond_bar =
        d.translation_mm > options.success_mm || d.rotation_deg > options.success_deg;
    if (check.nearest_dominating < 0) check.nearest_dominating = static_cast<int>(k);
    if (beyond_bar && check.nearest_dominating_beyond_bar < 0)
      check.nearest_dominating_beyond_bar = static_cast<int>(k);
    if (check.most_contact_dominating < 0 ||
        e.contact_area_mm2 > check.path[static_cast<std::size_t>(check.most_contact_dominating)]
                                 .evaluation.contact_area_mm2) {
      check.most_contact_dominating = static_cast<int>(k);
    }
  }
  return check;
}

struct Job {
  SolverKind solver;
  std::size_t magnitude;
  int start;
};

}  // namespace

std::vector<Magnitude> ParseMagnitudes(const std::string& text) {
  std::vector<Magnitude> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const auto colon = item.find(':');
    try {
      if (colon == std::string::npos) throw std::invalid_argument("no colon");
      std::size_t used_mm = 0, used_deg = 0;
      const std::string mm = item.substr(0, colon), deg = item.substr(colon + 1);
      Magnitude m{std::stod(mm, &used_mm), std::stod(deg, &used_deg)};
      if (used_mm != mm.size() || used_deg != deg.size() || !(m.mm >= 0.0 && m.mm <= 20.0) ||
          !(m.deg >= 0.0 && m.deg <= 45.0)) {
        throw std::invalid_argument("range");
      }
      out.push_back(m);
    } catch (const std::exception&) {
      throw UserError("--magnitudes: '" + item +
                      "' is not MM:DEG with 0 <= MM <= 20 and 0 <= DEG <= 45 (e.g. 1:2,2:3,5:10)");
    }
  }
  if (out.empty()) throw UserError("--magnitudes: give at least one MM:DEG (e.g. 1:2,2:3,5:10)");
  return out;
}

namespace {

// What every run shares: the schedule's last stage, the reference pose, its reference points
// in U and its pivot in L, and the request the runs start from.
struct Setup {
  const planner::OwnedSchedule* schedule = nullptr;
  Eigen::Isometry3d X_ref = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3d> points_U;
  Eigen::Vector3d pivot_L = Eigen::Vector3d::Zero();
  planner::PlanRequest base;
};

}  // namespace

void RunInParallel(std::size_t count, const ValidateOptions& options,
                   const std::function<void(std::size_t)>& run) {
  std::atomic<std::size_t> next{0}, done{0};
  std::mutex log_mutex;
  auto worker = [&]() {
    for (std::size_t j = next++; j < count; j = next++) {
      run(j);
      const std::size_t n = ++done;
      if (options.log && (n % 10 == 0 || n == count)) {
        std::lock_guard<std::mutex> lock(log_mutex);
        *options.log << "validate: " << n << " / " << count << " runs\n" << std::flush;
      }
    }
  };
  const int threads =
      options.threads > 0 ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
}

planner::PlanRequest BaseRequest(const ValidateOptions& options) {
  planner::PlanRequest base;
  base.contact_band_mm = options.contact_band_mm;
  base.max_penetration_mm = options.max_penetration_mm;
  base.num_threads = 1;
  base.max_proposals = 1;
  base.num_global_samples = options.global_samples;
  base.nlopt_local = options.nlopt_local;
  return base;
}

planner::PlanRequest BoundedRequest(const ValidateOptions& options, const Magnitude& magnitude,
                                    planner::SolverKind solver,
                                    const Eigen::Isometry3d& X_LU_start) {
  planner::PlanRequest req = BaseRequest(options);
  req.solver = solver;
  req.X_LU_start = X_LU_start;
  const double mm = magnitude.mm + options.bound_margin_mm;
  const double deg = magnitude.deg + options.bound_margin_deg;
  req.lower_bound.translation_mm = Eigen::Vector3d::Constant(-mm);
  req.upper_bound.translation_mm = Eigen::Vector3d::Constant(mm);
  req.lower_bound.rotation_deg = Eigen::Vector3d::Constant(-deg);
  req.upper_bound.rotation_deg = Eigen::Vector3d::Constant(deg);
  const bool multi = solver == SolverKind::kCoarseToFine || solver == SolverKind::kNloptGlobal;
  req.num_starts = multi ? options.solver_starts : 1;
  return req;
}

// The perturbed starts per magnitude, seeded per (magnitude, start), shared by all solvers.
std::vector<std::vector<PoseParameters>> Perturbations(const ValidateOptions& options) {
  std::vector<std::vector<PoseParameters>> perturb(options.magnitudes.size());
  for (std::size_t m = 0; m < options.magnitudes.size(); ++m) {
    for (int k = 0; k < options.starts; ++k) {
      std::mt19937 rng(options.seed * 1000003u + static_cast<std::uint32_t>(m) * 7919u +
                       static_cast<std::uint32_t>(k));
      PoseParameters p;
      p.translation_mm = InBall(rng, options.magnitudes[m].mm);
      p.rotation_deg = InBall(rng, options.magnitudes[m].deg);
      perturb[m].push_back(p);
    }
  }
  return perturb;
}

namespace {

// One solver from one perturbed start, within the magnitude plus the bound margins.
ValidateRun RunJob(const Job& job, const PoseParameters& perturbation, const Setup& setup,
                   const ValidateOptions& options) {
  const Magnitude& mag = options.magnitudes[job.magnitude];
  planner::PlanRequest req = BoundedRequest(
      options, mag, job.solver, planner::ComposePose(perturbation, setup.pivot_L, setup.X_ref));
  req.seed = options.seed + static_cast<std::uint32_t>(job.magnitude) * 1009u +
             static_cast<std::uint32_t>(job.start);
  const double c0 = ThreadCpuSeconds();
  const planner::PlanResult plan = planner::Plan(setup.schedule->stages, req);
  ValidateRun run;
  run.seconds = ThreadCpuSeconds() - c0;
  run.solver = job.solver;
  run.magnitude = mag;
  run.start = job.start;
  run.start_error = planner::ComparePoses(req.X_LU_start, setup.X_ref, setup.points_U);
  const planner::Proposal& best = plan.proposals.front();
  run.X_LU = best.X_LU;
  run.error = planner::ComparePoses(best.X_LU, setup.X_ref, setup.points_U);
  run.found = planner::DecomposePose(best.X_LU, setup.pivot_L, setup.X_ref);
  run.max_penetration_mm = best.evaluation.max_penetration_mm;
  run.constrained_penetration_mm = best.evaluation.constrained_penetration_mm;
  run.contact_area_mm2 = best.evaluation.contact_area_mm2;
  run.contact_samples = best.evaluation.contact_samples;
  run.outliers = best.evaluation.outliers.size();
  run.status = planner::ToString(best.status);
  run.evaluations = plan.total_evaluations;
  run.success = run.error.translation_mm <= options.success_mm &&
                run.error.rotation_deg <= options.success_deg;
  return run;
}

// Every (magnitude, start, solver) run, in that order, on options.threads threads (each run
// single-threaded; the results do not depend on the thread count).
std::vector<ValidateRun> RunJobs(const Setup& setup, const ValidateOptions& options) {
  const std::vector<std::vector<PoseParameters>> perturb = Perturbations(options);
  std::vector<Job> jobs;
  for (std::size_t m = 0; m < options.magnitudes.size(); ++m) {
    for (int k = 0; k < options.starts; ++k) {
      for (const SolverKind s : options.solvers) jobs.push_back({s, m, k});
    }
  }
  std::vector<ValidateRun> runs(jobs.size());
  RunInParallel(jobs.size(), options, [&](std::size_t j) {
    const Job& job = jobs[j];
    runs[j] =
        RunJob(job, perturb[job.magnitude][static_cast<std::size_t>(job.start)], setup, options);
  });
  return runs;
}

// The summary of one solver and magnitude, and each run's distance from their consensus.
ValidateSummary SummarizeGroup(const std::vector<ValidateRun*>& group, SolverKind solver,
                               const Magnitude& magnitude,
                               const std::vector<Eigen::Vector3d>& points_U,
                               const ValidateOptions& options) {
  const std::size_t medoid =
      Medoid(std::vector<const ValidateRun*>(group.begin(), group.end()), points_U);
  ValidateSummary row;
  row.solver = solver;
  row.magnitude = magnitude;
  row.runs = static_cast<int>(group.size());
  std::vector<double> em, ed, sec, cons;
  int ok = 0, near = 0;
  for (ValidateRun* r : group) {
    const PoseError c = planner::ComparePoses(r->X_LU, group[medoid]->X_LU, points_U);
    r->consensus_mm = c.translation_mm;
    cons.push_back(c.translation_mm);
    near += c.translation_mm <= options.success_mm && c.rotation_deg <= options.success_deg ? 1 : 0;
    em.push_back(r->error.translation_mm);
    ed.push_back(r->error.rotation_deg);
    sec.push_back(r->seconds);
    ok += r->success ? 1 : 0;
    row.worst_penetration_mm = std::max(row.worst_penetration_mm, r->constrained_penetration_mm);
    row.worst_max_penetration_mm = std::max(row.worst_max_penetration_mm, r->max_penetration_mm);
  }
  const double n = static_cast<double>(group.size());
  row.success_rate = ok / n;
  row.within_consensus = near / n;
  row.median_err_mm = NearestRankPercentile(em, 0.5, 0.0);
  row.p95_err_mm = NearestRankPercentile(em, 0.95, 0.0);
  row.median_err_deg = NearestRankPercentile(ed, 0.5, 0.0);
  row.p95_err_deg = NearestRankPercentile(ed, 0.95, 0.0);
  row.median_seconds = NearestRankPercentile(sec, 0.5, 0.0);
  row.median_consensus_mm = NearestRankPercentile(cons, 0.5, 0.0);
  row.medoid_error = group[medoid]->error;
  row.medoid_contact_mm2 = group[medoid]->contact_area_mm2;
  return row;
}

// Summaries and the consensus (medoid) per solver and magnitude.
std::vector<ValidateSummary> Summaries(std::vector<ValidateRun>* runs,
                                       const std::vector<Eigen::Vector3d>& points_U,
                                       const ValidateOptions& options) {
  std::vector<ValidateSummary> summary;
  for (const SolverKind s : options.solvers) {
    for (const Magnitude& magnitude : options.magnitudes) {
      std::vector<ValidateRun*> group;
      for (auto& r : *runs) {
        if (r.solver == s && r.magnitude.mm == magnitude.mm && r.magnitude.deg == magnitude.deg) {
          group.push_back(&r);
        }
      }
      if (!group.empty()) summary.push_back(SummarizeGroup(group, s, magnitude, points_U, options));
    }
  }
  return summary;
}

}  // namespace

ValidateResult RunValidation(const JawPair& jaws, const ValidateOptions& options) {
  ValidateResult result;
  result.case_name = jaws.name;
  const double t0 = NowSeconds();
  const planner::OwnedSchedule schedule =
      planner::BuildSchedule(jaws.lower_L, jaws.upper_U, options.voxels_mm, options.exact_last);
  result.build_seconds = NowSeconds() - t0;
  const planner::OracleStage& last = schedule.stages.back();
  Setup setup;
  setup.schedule = &schedule;
  setup.X_ref = jaws.X_LU_ref;
  setup.points_U = planner::ArchReferencePoints_U(*jaws.upper_U, setup.X_ref, last.oracle->arch());
  setup.pivot_L = setup.X_ref * setup.points_U[0];
  setup.base = BaseRequest(options);
  result.reference = planner::EvaluatePose(last, setup.X_ref, setup.base);
  result.runs = RunJobs(setup, options);
  result.summary = Summaries(&result.runs, setup.points_U, options);
  result.reference_check = CheckReference(result.runs, last, setup.X_ref, setup.pivot_L,
                                          setup.points_U, setup.base, options);
  return result;
}

}  // namespace occlude::app
