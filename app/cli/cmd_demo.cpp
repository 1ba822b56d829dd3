// `occlude demo`: the main job on the built-in synthetic jaw pair (what scripts/demo
// runs): `occlude propose` on the embedded synthetic case from a start about 1.6 mm and
// 2 degrees off the designed bite, the report of the best proposal, and how far it lies
// from the designed bite (the ground truth, X_LU = identity). The case config is written
// beside the results (case.toml), so `occlude refine out/demo/case.toml` carries on from
// there. `--sweep` adds the query-timing sweep of both sphere trees through the bite
// (demo.txt, demo.json) and the case as mesh files.
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "base/output_files.h"
#include "base/timing.h"
#include "bench/sweep.h"
#include "cli/cache_options.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "config/case_config.h"
#include "occlude/angles.h"
#include "occlude/collision/collide.h"
#include "occlude/planner/pose.h"
#include "report/proposal_report.h"
#include "session/memory_guard.h"
#include "session/synthetic_case.h"
#include "session/tree_report.h"

namespace occlude::app {
namespace {

struct DemoArgs {
  std::size_t triangles = 20000;
  std::uint32_t seed = 1;
  double voxel_mm = 0.2;
  bool voxel_given =
      false;  ///< --voxel also sets the search's finest voxel (else picked for 0.02 mm)
  double delta_mm = 0.1;
  int reps = 30;
  std::string out = "out/demo";
  double memory_budget_mb = 0;
  CacheArgs cache;
  bool sweep = false;
};

// The embedded case: the synthetic pair, its designed bite perturbed (as examples/synthetic.toml).
std::string DemoConfig(const DemoArgs& args) {
  std::ostringstream s;
  s << "# The case `occlude demo` ran (the built-in synthetic pair; its designed bite is X_LU =\n"
    << "# identity). Edit [adjust] and run `occlude refine` on this file to carry on.\n"
    << "[case]\nname = \"synthetic demo\"\nup_axis = \"+y\"\n"
    << "[synthetic]\ntriangles = " << args.triangles << "\nseed = " << args.seed << "\n"
    << "[accuracy]\n"
    << (args.voxel_given ? "voxel_mm = " + std::to_string(args.voxel_mm)
                         : std::string("accuracy_mm = 0.02"))
    << "\n"
    << "[contact]\nband_mm = " << args.delta_mm << "\nmax_penetration_mm = 0.05\n"
    << "[solver]\nname = \"auto\"\nstarts = 8\nseed = " << args.seed << "\nproposals = 3\n"
    << "[start]\ntranslation_mm = [0.9, 1.2, -0.6]\nrotation_deg = [1.0, -1.5, 0.8]\n"
    << "[adjust]\ntranslation_mm = [0.0, 0.0, 0.0]\nrotation_deg = [0.0, 0.0, 0.0]\n"
    << "[output]\nfolder = \".\"\n";
  return s.str();
}

void RunSweepDemo(const DemoArgs& args) {
  io::SyntheticJawOptions options;
  options.triangles_per_jaw = args.triangles;
  options.seed = args.seed;
  double t0 = NowSeconds();
  const io::SyntheticJawPair jaws = MakeSyntheticOrExplain(options);
  std::cout << "demo: generated the synthetic jaw pair (" << jaws.upper_U.num_triangles() << " + "
            << jaws.lower_L.num_triangles() << " triangles, seed " << args.seed << ", "
            << jaws.contacts.size() << " known contacts) in " << 1e3 * (NowSeconds() - t0)
            << " ms\n";

  collision::SphereTreeOptions tree_options;
  tree_options.voxelize.voxel_size_mm = args.voxel_mm;
  std::ostringstream subject;
  subject << "--voxel " << args.voxel_mm;
  CheckMemory({subject.str(),
               "the sphere trees of both jaws",
               "--voxel",
               1e3,
               "lower --triangles",
               {ExtentOf("the synthetic lower jaw", jaws.lower_L),
                ExtentOf("the synthetic upper jaw", jaws.upper_U)}},
              SphereTreePairEstimate(jaws.lower_L, jaws.upper_U, tree_options), args.voxel_mm,
              ResolveMemoryBudget(args.memory_budget_mb));
  const auto lower = BuildTreeOrExplain(std::make_shared<io::TriangleMesh>(jaws.lower_L),
                                        tree_options, "lower jaw");
  const auto upper = BuildTreeOrExplain(std::make_shared<io::TriangleMesh>(jaws.upper_U),
                                        tree_options, "upper jaw");
  std::cout << "demo: built the implicit sphere trees\n  " << DescribeTree("lower", lower) << "\n  "
            << DescribeTree("upper", upper) << "\n";

  const collision::CollisionPair pair(lower, upper);  // A = lower (frame L), B = upper (frame U)
  SweepOptions sweep;
  sweep.axis_L = jaws.occlusal_axis_L;
  sweep.delta_mm = args.delta_mm;
  sweep.reps = args.reps;
  sweep.offsets_mm = {2.0, 1.0, 0.5, 0.3, 0.2, 0.1, 0.05, 0.0, -0.05, -0.1, -0.2};
  const std::vector<SweepRow> rows = RunSweep(pair, jaws.X_LU, sweep);
  std::ostringstream table;
  table
      << "Upper jaw moved along the occlusal axis from the ground-truth bite (offset > 0 = open).\n"
      << "voxel " << args.voxel_mm << " mm, delta " << args.delta_mm
      << " mm, explicit sphere tree, "
      << "median of " << args.reps << " runs (pairs: " << std::max(1, args.reps / 3)
      << ", exact: " << std::max(1, args.reps / 10)
      << "), one thread; thread CPU time in microseconds\n"
      << SweepTable(rows);
  std::cout << table.str();

  WriteSyntheticCase(jaws, options, args.out);
  std::ostringstream json;
  json << "{\n  \"triangles_per_jaw\": " << args.triangles << ", \"seed\": " << args.seed
       << ", \"voxel_mm\": " << args.voxel_mm << ", \"delta_mm\": " << args.delta_mm
       << ",\n  \"lower_tree\": " << TreeJson(lower) << ",\n  \"upper_tree\": " << TreeJson(upper)
       << ",\n  \"sweep\": " << SweepJson(rows) << "\n}\n";
  WriteFileAtomic(std::filesystem::path(args.out) / "demo.json", json.str());
  WriteFileAtomic(std::filesystem::path(args.out) / "demo.txt", table.str());
  std::cout << "demo: wrote " << args.out
            << "/{upper.stl, lower.stl, truth.json, landmarks.csv, demo.json, demo.txt}\n";
}

void RunDemo(const DemoArgs& args) {
  const std::filesystem::path out = std::filesystem::absolute(args.out).lexically_normal();
  const std::string text = DemoConfig(args);
  const CaseConfig config = WithCacheArgs(ParseCaseConfig(text, out / "case.toml"), args.cache);
  std::cout << "demo: occlude propose on the built-in synthetic pair (" << args.triangles
            << " triangles per jaw, seed " << args.seed
            << "), from a start 1.6 mm / 2 deg off the designed bite\n";
  const Eigen::Isometry3d X_LU = ProposeAndReport(config, out.string(), args.memory_budget_mb);
  WriteFileAtomic(out / "case.toml", text);
  // Against the ground truth (identity), at the arch's extent: the largest displacement of
  // the upper jaw's vertices, and the rotation angle.
  const io::SyntheticJawPair jaws = [&] {
    io::SyntheticJawOptions options;
    options.triangles_per_jaw = args.triangles;
    options.seed = args.seed;
    return MakeSyntheticOrExplain(options);
  }();
  double worst_mm = 0.0;
  for (const Eigen::Vector3d& v : jaws.upper_U.vertices)
    worst_mm = std::max(worst_mm, (X_LU * v - v).norm());
  const double angle_deg = DegreesFromRadians(Eigen::AngleAxisd(X_LU.linear()).angle());
  std::cout << "demo: proposal 1 lies within " << std::setprecision(3) << worst_mm
            << " mm (largest vertex displacement) and " << angle_deg
            << " deg of the designed bite; report in " << (out / "report.html").string()
            << "; refine with: occlude refine " << (out / "case.toml").string() << "\n";
  if (args.sweep) RunSweepDemo(args);
}

}  // namespace

void AddDemoCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "demo",
      "Run the main job on the built-in synthetic jaw pair: propose the occlusion from a "
      "perturbed start, report it, compare with the designed bite");
  auto args = std::make_shared<DemoArgs>();
  cmd->add_option("--triangles", args->triangles, "Triangle budget per jaw")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Generator seed")->capture_default_str();
  cmd->add_option(
         "--voxel", args->voxel_mm,
         "Voxel size of the --sweep and, when given, of the search's finest oracle (default: "
         "picked for 0.02 mm accuracy), mm")
      ->capture_default_str()
      ->check(PositiveMm());
  cmd->add_option("--delta", args->delta_mm, "Contact band, mm")
      ->capture_default_str()
      ->check(BandMm());
  cmd->add_option("--reps", args->reps, "Repetitions per timed query of the --sweep")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--out", args->out, "Output folder")->capture_default_str();
  cmd->add_flag("--sweep", args->sweep,
                "Also time the sphere-tree queries along the occlusal axis through the bite "
                "(demo.txt, demo.json)");
  AddMemoryBudgetOption(cmd, &args->memory_budget_mb);
  AddCacheOptions(cmd, &args->cache);
  cmd->callback([cmd, args] {
    args->voxel_given = cmd->count("--voxel") > 0;
    RunDemo(*args);
  });
}

}  // namespace occlude::app
