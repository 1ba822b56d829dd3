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

static std::string Fmt(const Eigen::Vector3d& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.3f %.3f %.3f)", v.x(), v.y(), v.z());
  return b;
}

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: %s <case folder|synthetic> <solver> [runs] [t_mm] [r_deg] [voxels] "
                 "[exact] [starts] [threads]\n",
                 argv[0]);
    return 2;
  }
  const std::string which = argv[1];
  const planner::SolverKind solver = planner::SolverKindFromName(argv[2]);
  const int runs = argc > 3 ? std::atoi(argv[3]) : 10;
  const double t_mm = argc > 4 ? std::atof(argv[4]) : 2.0;
  const double r_deg = argc > 5 ? std::atof(argv[5]) : 3.0;
  std::vector<double> voxels;
  std::stringstream vs(argc > 6 ? argv[6] : "0.8,0.4");
  for (std::string tok; std::getline(vs, tok, ',');) voxels.push_back(std::atof(tok.c_str()));
  const bool exact = argc > 7 && std::atoi(argv[7]) != 0;
  const int starts = argc > 8 ? std::atoi(argv[8]) : 1;
  const int threads = argc > 9 ? std::atoi(argv[9]) : 1;

  std::shared_ptr<io::TriangleMesh> lower, upper;
  Eigen::Isometry3d X_true = Eigen::Isometry3d::Identity();
  if (which == "synthetic") {
    io::SyntheticJawOptions o;
    o.triangles_per_jaw = 10000;
    auto pair = io::MakeSyntheticJawPair(o);
    lower = std::make_shared<io::TriangleMesh>(pair.lower_L);
    upper = std::make_shared<io::TriangleMesh>(pair.upper_U);
    X_true = pair.X_LU;
  } else {
    lower = std::make_shared<io::TriangleMesh>(io::LoadMesh(which + "/lower.stl"));
    upper = std::make_shared<io::TriangleMesh>(io::LoadMesh(which + "/upper.stl"));
  }
  const planner::OwnedSchedule schedule = planner::BuildSchedule(lower, upper, voxels, exact);
  const auto& arch = schedule.stages.back().oracle->arch();
  const auto points_U = planner::ArchReferencePoints_U(*upper, X_true, arch);
  const Eigen::Vector3d pivot_true = X_true * points_U[0];
  std::printf("case %s solver %s voxels %s exact %d, perturbation %.2f mm / %.2f deg\n",
              which.c_str(), planner::ToString(solver), argc > 6 ? argv[6] : "0.8,0.4",
              exact ? 1 : 0, t_mm, r_deg);
  {
    // The registered pose itself, only settled along the occlusal axis: what the target scores.
    planner::PlanRequest req;
    req.solver = planner::SolverKind::kNloptLocal;
    req.X_LU_start = X_true;
    req.locked = {true, false, true, true, true, true};
    req.num_starts = 1;
    const planner::PlanResult res = planner::Plan(schedule.stages, req);
    const auto& p = res.proposals.front();
    std::printf(
        "truth settled: moved %.3f mm, max pen %.3f, constrained %.3f, contact %.2f mm2, outliers "
        "%zu\n",
        p.params.translation_mm.norm(), p.evaluation.max_penetration_mm,
        p.evaluation.constrained_penetration_mm, p.evaluation.contact_area_mm2,
        p.evaluation.outliers.size());
  }
  // Diagnostic (OCCLUDE_MEASURE_REVERSE=1): the collision check is one-sided (upper samples in
  // the lower's field); a swapped oracle measures lower samples in the upper's field.
  std::unique_ptr<collision::JawOracle> reverse;
  if (std::getenv("OCCLUDE_MEASURE_REVERSE")) {
    collision::OracleOptions o;
    o.voxel_size_mm = voxels.back();
    reverse = std::make_unique<collision::JawOracle>(upper, lower, o);
  }
  auto reverse_pen = [&](const Eigen::Isometry3d& X_LU, double* area) {
    collision::OracleRequest q;
    q.level = collision::AccuracyLevel::kSubVoxel;
    collision::OracleResult r;
    reverse->Query(X_LU.inverse(), q, &r);
    *area = r.penetration_area_mm2;
    return r.max_penetration_mm;
  };
  if (reverse) {
    double a = 0.0;
    const double p = reverse_pen(X_true, &a);
    std::printf("reverse check at the truth: lower in upper max %.3f mm, area %.3f mm2\n", p, a);
  }
  std::printf("run  err_mm  err_deg  maxpen  conspen  contact  cpu_s   evals  status\n");
  std::vector<double> et, er, cpu;
  int success = 0;
  for (int run = 0; run < runs; ++run) {
    std::mt19937 rng(1000 + static_cast<unsigned>(run));
    std::normal_distribution<double> g(0.0, 1.0);
    planner::PoseParameters perturb;
    perturb.translation_mm = t_mm * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    perturb.rotation_deg = r_deg * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    planner::PlanRequest req;
    req.solver = solver;
    req.X_LU_start = planner::ComposePose(perturb, pivot_true, X_true);
    req.lower_bound.translation_mm = Eigen::Vector3d::Constant(-(t_mm + 1.5));
    req.upper_bound.translation_mm = Eigen::Vector3d::Constant(t_mm + 1.5);
    req.lower_bound.rotation_deg = Eigen::Vector3d::Constant(-(r_deg + 3.0));
    req.upper_bound.rotation_deg = Eigen::Vector3d::Constant(r_deg + 3.0);
    req.num_starts = starts;
    if (const char* mp = std::getenv("OCCLUDE_MEASURE_MAXPEN"))
      req.max_penetration_mm = std::atof(mp);
    if (const char* ar = std::getenv("OCCLUDE_MEASURE_RANGE"))
      req.attraction_range_mm = std::atof(ar);
    if (const char* sw = std::getenv("OCCLUDE_MEASURE_SEAT")) {  // window,scale,allowance (mm)
      std::sscanf(sw, "%lf,%lf,%lf", &req.seat_window_mm, &req.seat_scale_mm,
                  &req.seat_penetration_allowance_mm);
    }
    if (const char* fc = std::getenv("OCCLUDE_MEASURE_FACING")) req.seat_min_facing = std::atof(fc);
    if (const char* nm = std::getenv("OCCLUDE_MEASURE_NLOPT"))
      req.nlopt_local = planner::NloptLocalMethodFromName(nm);
    if (const char* me = std::getenv("OCCLUDE_MEASURE_MAXEVAL"))
      req.max_evaluations = std::atoi(me);
    if (const char* k = std::getenv("OCCLUDE_MEASURE_K")) req.max_proposals = std::atoi(k);
    if (const char* gs = std::getenv("OCCLUDE_MEASURE_GLOBAL"))
      req.num_global_samples = std::atoi(gs);
    req.num_threads = threads;
    req.seed = static_cast<std::uint32_t>(run + 1);
    const planner::PlanResult res = planner::Plan(schedule.stages, req);
    const planner::Proposal& best = res.proposals.front();
    const planner::PoseError e = planner::ComparePoses(best.X_LU, X_true, points_U);
    et.push_back(e.translation_mm);
    er.push_back(e.rotation_deg);
    cpu.push_back(res.cpu_seconds);
    if (e.translation_mm <= 0.3 && e.rotation_deg <= 1.0) ++success;
    std::printf("%3d  %6.3f  %7.3f  %6.3f  %7.3f  %7.2f  %6.2f  %6d  %s\n", run, e.translation_mm,
                e.rotation_deg, best.evaluation.max_penetration_mm,
                best.evaluation.constrained_penetration_mm, best.evaluation.contact_area_mm2,
                res.cpu_seconds, res.total_evaluations, planner::ToString(best.status));
    if (reverse) {
      double a = 0.0;
      const double p = reverse_pen(best.X_LU, &a);
      std::printf("     reverse check: lower in upper max %.3f mm, area %.3f mm2\n", p, a);
    }
    if (const char* dir =
            std::getenv("OCCLUDE_MEASURE_POSES")) {  // pose files for `occlude report --pose`
      const std::string file = std::string(dir) + "/run" + std::to_string(run) + ".json";
      if (std::FILE* f = std::fopen(file.c_str(), "w")) {
        const Eigen::Matrix4d m = best.X_LU.matrix();
        std::fprintf(f, "{\"X_LU\": [");
        for (int r = 0; r < 4; ++r) {
          std::fprintf(f, "%s[%.17g, %.17g, %.17g, %.17g]", r ? ", " : "", m(r, 0), m(r, 1),
                       m(r, 2), m(r, 3));
        }
        std::fprintf(f, "]}\n");
        std::fclose(f);
      }
    }
    if (std::getenv("OCCLUDE_MEASURE_VERBOSE")) {
      const planner::PoseParameters d = planner::DecomposePose(best.X_LU, pivot_true, X_true);
      std::printf("     delta t %s  r %s  (occlusal %s)\n", Fmt(d.translation_mm).c_str(),
                  Fmt(d.rotation_deg).c_str(), Fmt(arch.occlusal_L).c_str());
    }
    std::fflush(stdout);
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  std::printf("median error %.3f mm %.3f deg, success (<=0.3 mm, 1 deg) %d/%d, median cpu %.2f s\n",
              median(et), median(er), success, runs, median(cpu));
  return 0;
}
