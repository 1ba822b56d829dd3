// Measures the planner: perturbs a known bite (a real registered case or the
// synthetic pair) by a fixed translation and rotation in random directions,
// runs a solver from there and prints the pose error at the pivot and at
// incisor/molar reference points, the penetration and the thread CPU time.
//
//   occlude_plan_measure <case folder | synthetic> <solver> [runs=10] [translation_mm=2]
//                        [rotation_deg=3] [voxels=0.8,0.4] [exact=0|1] [starts=1] [threads=1]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "occlude/io/mesh_io.h"
#include "occlude/io/synthetic_jaws.h"
#include "occlude/planner/plan.h"

using namespace occlude;

namespace {

std::string Fmt(const Eigen::Vector3d& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.3f %.3f %.3f)", v.x(), v.y(), v.z());
  return b;
}

struct Options {
  std::string which;
  planner::SolverKind solver = planner::SolverKind::kCoarseToFine;
  int runs = 10, starts = 1, threads = 1;
  double t_mm = 2.0, r_deg = 3.0;
  std::string voxel_list = "0.8,0.4";
  std::vector<double> voxels;
  bool exact = false;
};

Options ParseOptions(int argc, char** argv) {
  Options o;
  o.which = argv[1];
  o.solver = planner::SolverKindFromName(argv[2]);
  o.runs = argc > 3 ? std::atoi(argv[3]) : 10;
  o.t_mm = argc > 4 ? std::atof(argv[4]) : 2.0;
  o.r_deg = argc > 5 ? std::atof(argv[5]) : 3.0;
  if (argc > 6) o.voxel_list = argv[6];
  std::stringstream vs(o.voxel_list);
  for (std::string tok; std::getline(vs, tok, ',');) o.voxels.push_back(std::atof(tok.c_str()));
  o.exact = argc > 7 && std::atoi(argv[7]) != 0;
  o.starts = argc > 8 ? std::atoi(argv[8]) : 1;
  o.threads = argc > 9 ? std::atoi(argv[9]) : 1;
  return o;
}

struct Pair {
  std::shared_ptr<io::TriangleMesh> lower, upper;
  Eigen::Isometry3d X_true = Eigen::Isometry3d::Identity();
};

Pair LoadPair(const std::string& which) {
  Pair c;
  if (which == "synthetic") {
    io::SyntheticJawOptions o;
    o.triangles_per_jaw = 10000;
    auto pair = io::MakeSyntheticJawPair(o);
    c.lower = std::make_shared<io::TriangleMesh>(pair.lower_L);
    c.upper = std::make_shared<io::TriangleMesh>(pair.upper_U);
    c.X_true = pair.X_LU;
  } else {
    c.lower = std::make_shared<io::TriangleMesh>(io::LoadMesh(which + "/lower.stl"));
    c.upper = std::make_shared<io::TriangleMesh>(io::LoadMesh(which + "/upper.stl"));
  }
  return c;
}

// The registered pose itself, only settled along the occlusal axis: what the target scores.
void PrintTruthSettled(const planner::OracleSchedule& stages, const Eigen::Isometry3d& X_true) {
  planner::PlanRequest req;
  req.solver = planner::SolverKind::kNloptLocal;
  req.X_LU_start = X_true;
  req.locked = {true, false, true, true, true, true};
  req.num_starts = 1;
  const planner::PlanResult res = planner::Plan(stages, req);
  const auto& p = res.proposals.front();
  std::printf(
      "truth settled: moved %.3f mm, max pen %.3f, constrained %.3f, contact %.2f mm2, outliers "
      "%zu\n",
      p.params.translation_mm.norm(), p.evaluation.max_penetration_mm,
      p.evaluation.constrained_penetration_mm, p.evaluation.contact_area_mm2,
      p.evaluation.outliers.size());
}

// The request's settings the environment overrides (OCCLUDE_MEASURE_*).
void ApplyEnvironment(planner::PlanRequest* req) {
  if (const char* mp = std::getenv("OCCLUDE_MEASURE_MAXPEN"))
    req->max_penetration_mm = std::atof(mp);
  if (const char* ar = std::getenv("OCCLUDE_MEASURE_RANGE"))
    req->attraction_range_mm = std::atof(ar);
  if (const char* sw = std::getenv("OCCLUDE_MEASURE_SEAT")) {  // window,scale,allowance (mm)
    std::sscanf(sw, "%lf,%lf,%lf", &req->seat_window_mm, &req->seat_scale_mm,
                &req->seat_penetration_allowance_mm);
  }
  if (const char* fc = std::getenv("OCCLUDE_MEASURE_FACING")) req->seat_min_facing = std::atof(fc);
  if (const char* nm = std::getenv("OCCLUDE_MEASURE_NLOPT"))
    req->nlopt_local = planner::NloptLocalMethodFromName(nm);
  if (const char* me = std::getenv("OCCLUDE_MEASURE_MAXEVAL")) req->max_evaluations = std::atoi(me);
  if (const char* k = std::getenv("OCCLUDE_MEASURE_K")) req->max_proposals = std::atoi(k);
  if (const char* gs = std::getenv("OCCLUDE_MEASURE_GLOBAL"))
    req->num_global_samples = std::atoi(gs);
}

// Run `run`'s request: the truth perturbed by t_mm / r_deg in seeded random directions.
planner::PlanRequest RunRequest(const Options& o, int run, const Eigen::Vector3d& pivot_true,
                                const Eigen::Isometry3d& X_true) {
  std::mt19937 rng(1000 + static_cast<unsigned>(run));
  std::normal_distribution<double> g(0.0, 1.0);
  planner::PoseParameters perturb;
  perturb.translation_mm = o.t_mm * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
  perturb.rotation_deg = o.r_deg * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
  planner::PlanRequest req;
  req.solver = o.solver;
  req.X_LU_start = planner::ComposePose(perturb, pivot_true, X_true);
  req.lower_bound.translation_mm = Eigen::Vector3d::Constant(-(o.t_mm + 1.5));
  req.upper_bound.translation_mm = Eigen::Vector3d::Constant(o.t_mm + 1.5);
  req.lower_bound.rotation_deg = Eigen::Vector3d::Constant(-(o.r_deg + 3.0));
  req.upper_bound.rotation_deg = Eigen::Vector3d::Constant(o.r_deg + 3.0);
  req.num_starts = o.starts;
  ApplyEnvironment(&req);
  req.num_threads = o.threads;
  req.seed = static_cast<std::uint32_t>(run + 1);
  return req;
}

// A pose file for `occlude report --pose` (OCCLUDE_MEASURE_POSES=<folder>).
void WritePoseFile(const char* dir, int run, const Eigen::Isometry3d& X_LU) {
  const std::string file = std::string(dir) + "/run" + std::to_string(run) + ".json";
  if (std::FILE* f = std::fopen(file.c_str(), "w")) {
    const Eigen::Matrix4d m = X_LU.matrix();
    std::fprintf(f, "{\"X_LU\": [");
    for (int r = 0; r < 4; ++r) {
      std::fprintf(f, "%s[%.17g, %.17g, %.17g, %.17g]", r ? ", " : "", m(r, 0), m(r, 1), m(r, 2),
                   m(r, 3));
    }
    std::fprintf(f, "]}\n");
    std::fclose(f);
  }
}

// Diagnostic (OCCLUDE_MEASURE_REVERSE=1): the collision check is one-sided (upper samples in
// the lower's field); a swapped oracle measures lower samples in the upper's field.
struct ReverseCheck {
  std::unique_ptr<collision::JawOracle> oracle;
  void Print(const char* what, const Eigen::Isometry3d& X_LU) const {
    if (!oracle) return;
    collision::OracleRequest q;
    q.level = collision::AccuracyLevel::kSubVoxel;
    collision::OracleResult r;
    oracle->Query(X_LU.inverse(), q, &r);
    std::printf("%s: lower in upper max %.3f mm, area %.3f mm2\n", what, r.max_penetration_mm,
                r.penetration_area_mm2);
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: %s <case folder|synthetic> <solver> [runs] [t_mm] [r_deg] [voxels] "
                 "[exact] [starts] [threads]\n",
                 argv[0]);
    return 2;
  }
  const Options o = ParseOptions(argc, argv);
  const Pair c = LoadPair(o.which);
  const planner::OwnedSchedule schedule =
      planner::BuildSchedule(c.lower, c.upper, o.voxels, o.exact);
  const auto& arch = schedule.stages.back().oracle->arch();
  const auto points_U = planner::ArchReferencePoints_U(*c.upper, c.X_true, arch);
  const Eigen::Vector3d pivot_true = c.X_true * points_U[0];
  std::printf("case %s solver %s voxels %s exact %d, perturbation %.2f mm / %.2f deg\n",
              o.which.c_str(), planner::ToString(o.solver), o.voxel_list.c_str(), o.exact ? 1 : 0,
              o.t_mm, o.r_deg);
  PrintTruthSettled(schedule.stages, c.X_true);
  ReverseCheck reverse;
  if (std::getenv("OCCLUDE_MEASURE_REVERSE")) {
    collision::OracleOptions ro;
    ro.voxel_size_mm = o.voxels.back();
    reverse.oracle = std::make_unique<collision::JawOracle>(c.upper, c.lower, ro);
  }
  reverse.Print("reverse check at the truth", c.X_true);
  std::printf("run  err_mm  err_deg  maxpen  conspen  contact  cpu_s   evals  status\n");
  std::vector<double> et, er, cpu;
  int success = 0;
  for (int run = 0; run < o.runs; ++run) {
    const planner::PlanResult res =
        planner::Plan(schedule.stages, RunRequest(o, run, pivot_true, c.X_true));
    const planner::Proposal& best = res.proposals.front();
    const planner::PoseError e = planner::ComparePoses(best.X_LU, c.X_true, points_U);
    et.push_back(e.translation_mm);
    er.push_back(e.rotation_deg);
    cpu.push_back(res.cpu_seconds);
    if (e.translation_mm <= 0.3 && e.rotation_deg <= 1.0) ++success;
    std::printf("%3d  %6.3f  %7.3f  %6.3f  %7.3f  %7.2f  %6.2f  %6d  %s\n", run, e.translation_mm,
                e.rotation_deg, best.evaluation.max_penetration_mm,
                best.evaluation.constrained_penetration_mm, best.evaluation.contact_area_mm2,
                res.cpu_seconds, res.total_evaluations, planner::ToString(best.status));
    reverse.Print("     reverse check", best.X_LU);
    if (const char* dir = std::getenv("OCCLUDE_MEASURE_POSES")) WritePoseFile(dir, run, best.X_LU);
    if (std::getenv("OCCLUDE_MEASURE_VERBOSE")) {
      const planner::PoseParameters d = planner::DecomposePose(best.X_LU, pivot_true, c.X_true);
      std::printf("     delta t %s  r %s  (occlusal %s)\n", Fmt(d.translation_mm).c_str(),
                  Fmt(d.rotation_deg).c_str(), Fmt(arch.occlusal_L).c_str());
    }
    std::fflush(stdout);
  }
  std::sort(et.begin(), et.end());
  std::sort(er.begin(), er.end());
  std::sort(cpu.begin(), cpu.end());
  auto median = [](const std::vector<double>& v) { return v.empty() ? 0.0 : v[v.size() / 2]; };
  std::printf("median error %.3f mm %.3f deg, success (<=0.3 mm, 1 deg) %d/%d, median cpu %.2f s\n",
              median(et), median(er), success, o.runs, median(cpu));
  return 0;
}
