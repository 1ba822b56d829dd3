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
#include "occlude/collision/collide.h"
#include "output_files.h"
#include "synthetic_case.h"
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
};

struct OffsetRow {
  double offset_mm = 0.0;
  bool overlap = false;
  Summary boolean_us, pairs_us, exact_us;
  std::size_t pairs = 0, contacts = 0;
  double min_distance_mm = 0.0;
  bool intersect = false;
};

OffsetRow Measure(const collision::CollisionPair& pair, const Eigen::Isometry3d& X_LU,
                  const DemoArgs& args) {
  OffsetRow row;
  collision::CollisionRequest req;
  collision::CollisionResult res;
  req.first_only = true;
  row.boolean_us = TimeMicros([&] { pair.Query(X_LU, req, &res); }, args.reps);
  row.overlap = res.overlap;
  req.first_only = false;
  req.delta_mm = args.delta_mm;
  row.pairs_us = TimeMicros([&] { pair.Query(X_LU, req, &res); }, args.reps);
  row.pairs = res.pairs.size();
  req.exact = true;
  row.exact_us = TimeMicros([&] { pair.Query(X_LU, req, &res); }, std::max(1, args.reps / 5));
  row.contacts = res.contacts.size();
  row.min_distance_mm = res.min_distance_mm;
  row.intersect = res.triangles_intersect;
  return row;
}

std::string RowText(const OffsetRow& r) {
  char line[256];
  char dist[32];
  if (std::isfinite(r.min_distance_mm)) {
    std::snprintf(dist, sizeof dist, "%.4f", r.min_distance_mm);
  } else {
    std::snprintf(dist, sizeof dist, "> delta");
  }
  std::snprintf(line, sizeof line, "%+7.2f  %-7s %9.1f  %8zu %9.1f  %8zu %9s  %-9s %9.1f", r.offset_mm,
                r.overlap ? "yes" : "no", r.boolean_us.median, r.pairs, r.pairs_us.median,
                r.contacts, dist, r.intersect ? "yes" : "no", r.exact_us.median);
  return line;
}

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
  const auto lower = BuildTreeOrExplain(std::make_shared<io::TriangleMesh>(jaws.lower_L),
                                        tree_options, "lower jaw");
  const auto upper = BuildTreeOrExplain(std::make_shared<io::TriangleMesh>(jaws.upper_U),
                                        tree_options, "upper jaw");
  std::cout << "demo: built the implicit sphere trees\n  " << DescribeTree("lower", lower)
            << "\n  " << DescribeTree("upper", upper) << "\n";

  const collision::CollisionPair pair(lower, upper);  // A = lower (frame L), B = upper (frame U)
  std::ostringstream table;
  table << "Upper jaw moved along the occlusal axis from the ground-truth bite (offset > 0 = open).\n"
        << "voxel " << args.voxel_mm << " mm, delta " << args.delta_mm << " mm, median of "
        << args.reps << " runs, one thread; times in microseconds\n"
        << " offset  overlap  bool_us     pairs  pairs_us  contacts  min_dist  intersect  exact_us\n";
  std::ostringstream rows_json;
  const double offsets[] = {2.0, 1.0, 0.5, 0.3, 0.2, 0.1, 0.05, 0.0, -0.05, -0.1, -0.2};
  for (const double offset : offsets) {
    const Eigen::Isometry3d X_LU = Eigen::Translation3d(offset * jaws.occlusal_axis_L) * jaws.X_LU;
    OffsetRow row = Measure(pair, X_LU, args);
    row.offset_mm = offset;
    table << RowText(row) << "\n";
    rows_json << (offset == offsets[0] ? "\n    " : ",\n    ") << "{\"offset_mm\": " << offset
              << ", \"overlap\": " << (row.overlap ? "true" : "false")
              << ", \"boolean_median_us\": " << row.boolean_us.median
              << ", \"voxel_pairs\": " << row.pairs << ", \"pairs_median_us\": " << row.pairs_us.median
              << ", \"exact_contacts\": " << row.contacts << ", \"min_distance_mm\": "
              << (std::isfinite(row.min_distance_mm) ? std::to_string(row.min_distance_mm) : "null")
              << ", \"triangles_intersect\": " << (row.intersect ? "true" : "false")
              << ", \"exact_median_us\": " << row.exact_us.median << "}";
  }
  std::cout << table.str();

  WriteSyntheticCase(jaws, options, args.out);
  std::ostringstream json;
  json << "{\n  \"triangles_per_jaw\": " << args.triangles << ", \"seed\": " << args.seed
       << ", \"voxel_mm\": " << args.voxel_mm << ", \"delta_mm\": " << args.delta_mm
       << ",\n  \"lower_tree\": " << TreeJson(lower) << ",\n  \"upper_tree\": " << TreeJson(upper)
       << ",\n  \"sweep\": [" << rows_json.str() << "\n  ]\n}\n";
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
      ->check(CLI::PositiveNumber);
  cmd->add_option("--delta", args->delta_mm, "Contact band, mm")->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--reps", args->reps, "Repetitions per timed query")->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--out", args->out, "Output folder")->capture_default_str();
  cmd->callback([args] { RunDemo(*args); });
}

}  // namespace occlude::app
