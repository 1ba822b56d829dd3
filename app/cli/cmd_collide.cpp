// `occlude collide`: loads a jaw pair (files or part files), builds both
// sphere trees, and answers one query at a pose: voxel pairs within the band,
// exact triangle contacts, minimum distance, interpenetration.
#include <iostream>
#include <memory>
#include <sstream>

#include "base/axis_name.h"
#include "base/output_files.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "bench/sweep.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "config/pose_file.h"
#include "occlude/collision/collide.h"
#include "occlude/io/mesh_io.h"
#include "session/jaw_checks.h"
#include "session/jaw_pair.h"
#include "session/memory_guard.h"
#include "session/tree_report.h"

namespace occlude::app {
namespace {

struct CollideArgs {
  std::vector<std::string> upper, lower;
  std::string units = "mm";
  std::string pose;
  double voxel_mm = 0.2;
  double delta_mm = 0.1;
  std::string out;
  bool sweep = false;
  std::string axis = "y";
  int reps = 30;
  double memory_budget_mb = 0;
};

// "x", "y", "z" with an optional sign ("-z").
Eigen::Vector3d ParseAxis(const std::string& text) {
  if (const std::optional<Eigen::Vector3d> axis = AxisFromName(text)) return *axis;
  throw UserError("--axis: '" + text + "' is not an axis (use x, y, z, -x, -y or -z)");
}

std::string FormatMm(double mm) {
  std::ostringstream s;
  s << mm;
  return s.str();
}

// The jaw's files: one mesh file, or several part files.
std::shared_ptr<const io::TriangleMesh> LoadJawFiles(const std::vector<std::string>& files,
                                                     io::LengthUnit unit) {
  const std::vector<std::filesystem::path> paths(files.begin(), files.end());
  return LoadJaw(paths, paths.size() != 1, unit);
}

void RunCollide(const CollideArgs& args) {
  const auto unit = io::ParseLengthUnit(args.units);
  if (!unit)
    throw UserError("--units: unknown unit '" + args.units + "' (use mm, cm, m, um or in)");
  if (!args.out.empty()) PrepareOutputDir(args.out);
  const Eigen::Isometry3d X_LU =
      args.pose.empty() ? Eigen::Isometry3d::Identity() : ReadPoseFile(args.pose);
  const auto lower_mesh = LoadJawFiles(args.lower, *unit);
  const auto upper_mesh = LoadJawFiles(args.upper, *unit);
  collision::SphereTreeOptions options;
  options.voxelize.voxel_size_mm = args.voxel_mm;
  const std::string lower_name = "lower jaw (" + JawFilesName(args.lower) + ")";
  const std::string upper_name = "upper jaw (" + JawFilesName(args.upper) + ")";
  for (const std::string& w : JawPairWarnings(*lower_mesh, *upper_mesh, X_LU,
                                              JawFilesName(args.lower), JawFilesName(args.upper))) {
    std::cerr << "occlude: warning: " << w << "\n";
  }
  CheckMemory({"--voxel " + FormatMm(args.voxel_mm),
               "the sphere trees of both jaws",
               "--voxel",
               1e3,
               "decimate the meshes",
               {ExtentOf(JawFilesName(args.lower), *lower_mesh),
                ExtentOf(JawFilesName(args.upper), *upper_mesh)}},
              SphereTreePairEstimate(*lower_mesh, *upper_mesh, options), args.voxel_mm,
              ResolveMemoryBudget(args.memory_budget_mb));
  const auto lower = BuildTreeOrExplain(lower_mesh, options, lower_name);
  const auto upper = BuildTreeOrExplain(upper_mesh, options, upper_name);
  std::cout << DescribeTree("lower", lower) << "\n" << DescribeTree("upper", upper) << "\n";

  collision::CollisionRequest req;
  req.delta_mm = args.delta_mm;
  req.exact = true;
  collision::CollisionResult res;
  const double t0 = NowSeconds();
  collision::Collide(lower, upper, X_LU, req, &res);
  const double seconds = NowSeconds() - t0;
  std::ostringstream s;
  s << "{\"voxel_mm\": " << args.voxel_mm << ", \"delta_mm\": " << args.delta_mm
    << ", \"voxel_pairs\": " << res.pairs.size() << ", \"node_tests\": " << res.node_tests
    << ", \"exact_contacts\": " << res.contacts.size()
    << ", \"triangles_intersect\": " << (res.triangles_intersect ? "true" : "false")
    << ", \"min_distance_mm\": "
    << (std::isfinite(res.min_distance_mm) ? std::to_string(res.min_distance_mm) : "null")
    << ", \"query_seconds\": " << seconds << ",\n \"lower_tree\": " << TreeJson(lower)
    << ",\n \"upper_tree\": " << TreeJson(upper) << "}\n";
  std::cout << "query (" << 1e3 * seconds << " ms): " << res.pairs.size() << " voxel pairs within "
            << args.delta_mm << " mm, " << res.contacts.size()
            << " triangle pairs within the band, "
            << (res.triangles_intersect ? "the jaws interpenetrate" : "no triangle intersection")
            << ", minimum distance "
            << (std::isfinite(res.min_distance_mm) ? std::to_string(res.min_distance_mm) + " mm"
                                                   : "more than the band")
            << "\n";
  if (!args.out.empty()) WriteFileAtomic(std::filesystem::path(args.out) / "collide.json", s.str());
  if (!args.sweep) return;

  SweepOptions sweep;
  sweep.axis_L = ParseAxis(args.axis);
  sweep.delta_mm = args.delta_mm;
  sweep.reps = args.reps;
  sweep.modes = {collision::SphereMode::kSimple, collision::SphereMode::kOptimized,
                 collision::SphereMode::kExplicit};
  const collision::CollisionPair pair(lower, upper);
  const std::vector<SweepRow> rows = RunSweep(pair, X_LU, sweep);
  std::ostringstream table;
  table << "Sweep along " << args.axis << " from the given pose (offset > 0 = open); voxel "
        << args.voxel_mm << " mm, delta " << args.delta_mm << " mm; median of " << args.reps
        << " runs, one thread; thread CPU time in microseconds\n"
        << SweepTable(rows);
  std::cout << table.str();
  if (!args.out.empty()) {
    WriteFileAtomic(std::filesystem::path(args.out) / "sweep.txt", table.str());
    WriteFileAtomic(std::filesystem::path(args.out) / "sweep.json", SweepJson(rows) + "\n");
  }
}

}  // namespace

void AddCollideCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "collide", "Build the sphere trees of a jaw pair and report contacts at one pose");
  auto args = std::make_shared<CollideArgs>();
  cmd->add_option("--lower", args->lower, "Lower jaw mesh file(s) (several = parts)")->required();
  cmd->add_option("--upper", args->upper, "Upper jaw mesh file(s) (several = parts)")->required();
  cmd->add_option("--units", args->units, "Unit of the mesh files: mm, cm, m, um, in")
      ->capture_default_str();
  cmd->add_option("--pose", args->pose, "Pose file (JSON with a 4x4 \"X_LU\"); default identity");
  cmd->add_option("--voxel", args->voxel_mm, "Voxel size, mm")
      ->capture_default_str()
      ->check(PositiveMm());
  cmd->add_option("--delta", args->delta_mm, "Contact band, mm")
      ->capture_default_str()
      ->check(BandMm());
  cmd->add_option("--out", args->out, "Output folder for collide.json (and sweep.txt/json)");
  AddMemoryBudgetOption(cmd, &args->memory_budget_mb);
  cmd->add_flag("--sweep", args->sweep,
                "Also sweep the upper jaw along --axis through the pose, timing every sphere mode");
  cmd->add_option("--axis", args->axis, "Sweep axis, lower to upper: x, y, z, -x, -y, -z")
      ->capture_default_str();
  cmd->add_option("--reps", args->reps, "Repetitions per timed query in the sweep")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->callback([args] { RunCollide(*args); });
}

}  // namespace occlude::app
