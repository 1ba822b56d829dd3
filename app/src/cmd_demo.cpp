// `occlude demo`: the main job on the built-in synthetic jaw pair (what
// scripts/demo runs). Generates the pair, builds both sphere trees, and sweeps
// the upper jaw along the occlusal axis through the ground-truth bite, timing
// the boolean, all-pairs and exact queries at each offset; writes the case,
// a table and a JSON summary to the output folder.
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.h"
#include "memory_guard.h"
#include "occlude/collision/collide.h"
#include "output_files.h"
#include "synthetic_case.h"
#include "sweep.h"
#include "timing.h"
#include "tree_report.h"

namespace occlude::app {
namespace {

struct DemoArgs {
  std::size_t triangles = 20000;
  std::uint32_t seed = 1;
  double voxel_mm = 0.2;
  double delta_mm = 0.1;
  int reps = 30;
  std::string out = "out/demo";
  double memory_budget_mb = 0;
};

void RunDemo(const DemoArgs& args) {
  PrepareOutputDir(args.out);
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
  CheckMemory({subject.str(), "the sphere trees of both jaws", "--voxel", 1e3, "lower --triangles",
               {ExtentOf("the synthetic lower jaw", jaws.lower_L), ExtentOf("the synthetic upper jaw", jaws.upper_U)}},
              SphereTreePairEstimate(jaws.lower_L, jaws.upper_U, tree_options),
              args.voxel_mm, ResolveMemoryBudget(args.memory_budget_mb));
  const auto lower = BuildTreeOrExplain(std::make_shared<io::TriangleMesh>(jaws.lower_L),
                                        tree_options, "lower jaw");
  const auto upper = BuildTreeOrExplain(std::make_shared<io::TriangleMesh>(jaws.upper_U),
                                        tree_options, "upper jaw");
  std::cout << "demo: built the implicit sphere trees\n  " << DescribeTree("lower", lower)
            << "\n  " << DescribeTree("upper", upper) << "\n";

  const collision::CollisionPair pair(lower, upper);  // A = lower (frame L), B = upper (frame U)
  SweepOptions sweep;
  sweep.axis_L = jaws.occlusal_axis_L;
  sweep.delta_mm = args.delta_mm;
  sweep.reps = args.reps;
  sweep.offsets_mm = {2.0, 1.0, 0.5, 0.3, 0.2, 0.1, 0.05, 0.0, -0.05, -0.1, -0.2};
  const std::vector<SweepRow> rows = RunSweep(pair, jaws.X_LU, sweep);
  std::ostringstream table;
  table << "Upper jaw moved along the occlusal axis from the ground-truth bite (offset > 0 = open).\n"
        << "voxel " << args.voxel_mm << " mm, delta " << args.delta_mm << " mm, explicit sphere tree, "
        << "median of " << args.reps << " runs (pairs: " << std::max(1, args.reps / 3)
        << ", exact: " << std::max(1, args.reps / 10) << "), one thread; thread CPU time in microseconds\n"
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
  std::cout << "demo: wrote " << args.out << "/{upper.stl, lower.stl, truth.json, demo.json, demo.txt}\n";
}

}  // namespace

void AddDemoCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("demo", "Run the main job on the built-in synthetic jaw pair");
  auto args = std::make_shared<DemoArgs>();
  cmd->add_option("--triangles", args->triangles, "Triangle budget per jaw")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Generator seed")->capture_default_str();
  cmd->add_option("--voxel", args->voxel_mm, "Voxel size, mm")->capture_default_str()
      ->check(PositiveMm());
  cmd->add_option("--delta", args->delta_mm, "Contact band, mm")->capture_default_str()
      ->check(BandMm());
  cmd->add_option("--reps", args->reps, "Repetitions per timed query")->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--out", args->out, "Output folder")->capture_default_str();
  AddMemoryBudgetOption(cmd, &args->memory_budget_mb);
  cmd->callback([args] { RunDemo(*args); });
}

}  // namespace occlude::app
