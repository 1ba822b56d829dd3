// `occlude bench`: the paper's query-rate experiment on a jaw pair, with FCL
// and OpenVDB side by side (CSV + PNG charts); `--haptic`, the fixed-period loop;
// `--paper`, the paper's result figures (bench_paper.h); `--accuracy`, speed
// against accuracy (bench_accuracy.h). This file holds the options and the
// dispatch; each mode's work lives in its own files.
#include <algorithm>
#include <iostream>
#include <sstream>

#include "base/output_files.h"
#include "base/user_error.h"
#include "bench/bench.h"
#include "bench/bench_accuracy.h"
#include "bench/bench_inputs.h"
#include "bench/bench_paper.h"
#include "bench/fcl_peer.h"
#include "bench/openvdb_peer.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "occlude/collision/oracle.h"
#include "session/jaw_pair.h"
#include "session/memory_guard.h"

namespace occlude::app {
namespace {

struct BenchArgs {
  std::string case_dir;
  std::size_t synthetic = 0;
  std::vector<double> voxels = {0.8, 0.4, 0.2, 0.1};
  std::vector<double> offsets;
  int reps = 15;
  int rounds = 3;
  std::uint32_t seed = 1;
  double delta_mm = 0.1;
  std::string axis = "auto";
  double jitter_deg = 0.2, jitter_mm = 0.05;
  bool no_fcl = false;
  bool no_openvdb = false;
  bool haptic = false;
  std::vector<double> periods = {1000.0, 100.0};
  double seconds = 2.0;
  std::string out;
  // --paper and --accuracy.
  bool paper = false, accuracy = false;
  std::string mesh;
  std::vector<double> sweep_voxels = {0.8, 0.2};
  bool no_sweep = false;
  int poses = 16;
  std::vector<double> offset_range = {-0.2, 1.0};
  double truth_spacing = 0.05;
  double memory_budget_mb = 0;
};

// The file of a jaw for messages.
std::string JawName(const BenchArgs& args, const std::string& jaw) {
  if (args.case_dir.empty()) return "the synthetic " + jaw + " jaw";
  return (std::filesystem::path(args.case_dir) / (jaw + ".stl")).string();
}

// The memory guard at the finest voxel size the run will use: the oracle there is
// the largest structure the bench builds (its sample spacing as in bench.cpp; FCL's
// trees are not counted).
void GuardBenchMemory(const BenchCase& bc, const std::vector<double>& voxels,
                      const BenchArgs& args) {
  if (voxels.empty()) return;
  const double finest = *std::min_element(voxels.begin(), voxels.end());
  std::ostringstream subject;
  subject << "--voxel " << finest;
  CheckMemory(
      {subject.str(),
       "the contact oracle",
       "the finest --voxel",
       5.0,
       "decimate the meshes",
       {ExtentOf(JawName(args, "lower"), *bc.lower_L),
        ExtentOf(JawName(args, "upper"), *bc.upper_U)}},
      [&](double voxel_mm) {
        collision::OracleOptions options;
        options.voxel_size_mm = voxel_mm;
        options.sample_spacing_mm = std::min(0.3, 1.5 * voxel_mm);
        return collision::EstimateOracleMemory(*bc.lower_L, *bc.upper_U, options);
      },
      finest, ResolveMemoryBudget(args.memory_budget_mb));
}

// Which of the shared options were given (the modes have their own defaults).
struct Given {
  bool voxels = false, reps = false, offsets = false, delta = false;
};

void RunPaperCommand(const BenchArgs& args, const Given& given) {
  PrepareOutputDir(args.out);
  PaperOptions options;
  if (given.voxels) options.voxels_mm = args.voxels;
  if (given.reps) options.reps = args.reps;
  if (given.offsets) options.offsets_mm = args.offsets;
  if (given.delta) options.delta_mm = args.delta_mm;
  options.sweep_voxels_mm = args.sweep_voxels;
  options.sweep = !args.no_sweep;
  options.seed = args.seed;
  options.fcl = !args.no_fcl;
  options.log = &std::cerr;
  const std::string machine = MachineLine();
  PaperResult result;
  if (!args.mesh.empty()) {
    const std::filesystem::path file(args.mesh);
    result = RunPaper(LoadExistingMesh(file, "--mesh needs a mesh file"), file.stem().string(),
                      nullptr, options);
  } else {
    const BenchCase bc = LoadBenchCase(args.case_dir, args.synthetic, args.seed, args.axis);
    result = RunPaper(bc.lower_L, bc.name + " lower", &bc, options);
  }
  for (const auto& [file, bytes] : PaperFiles(result, machine)) {
    WriteFileAtomic(std::filesystem::path(args.out) / file, bytes);
  }
  for (const auto& [file, bytes] : PaperFiles(result, machine)) {
    if (file == "paper-summary.txt") std::cout << bytes;
  }
  std::cerr << "bench: wrote the paper's figures to " << args.out << "\n";
}

void RunAccuracyCommand(const BenchArgs& args, const Given& given) {
  PrepareOutputDir(args.out);
  const BenchCase bc = LoadBenchCase(args.case_dir, args.synthetic, args.seed, args.axis);
  AccuracyOptions options;
  if (given.voxels) options.voxels_mm = args.voxels;
  if (given.reps) options.reps = args.reps;
  options.poses = args.poses;
  options.offset_lo_mm = args.offset_range[0];
  options.offset_hi_mm = args.offset_range[1];
  options.jitter_deg = args.jitter_deg;
  options.jitter_mm = args.jitter_mm;
  options.seed = args.seed;
  options.delta_mm = args.delta_mm;
  options.truth_spacing_mm = args.truth_spacing;
  options.fcl = !args.no_fcl;
  options.log = &std::cerr;
  const std::string machine = MachineLine();
  const std::vector<AccuracyRow> rows = RunAccuracy(bc, options);
  const std::string about =
      "occlude bench --accuracy, case " + bc.name + " (" +
      std::to_string(bc.lower_L->num_triangles()) + " lower / " +
      std::to_string(bc.upper_U->num_triangles()) + " upper triangles); machine: " + machine +
      "\n" + std::to_string(options.poses) + " poses: offsets in [" +
      std::to_string(options.offset_lo_mm) + ", " + std::to_string(options.offset_hi_mm) +
      "] mm along the occlusal axis, jitter up to " + std::to_string(options.jitter_deg) +
      " deg and " + std::to_string(options.jitter_mm) + " mm, seed " +
      std::to_string(options.seed) + "; delta " + std::to_string(options.delta_mm) +
      " mm; truth spacing " + std::to_string(options.truth_spacing_mm) + " mm";
  const std::filesystem::path out(args.out);
  const std::string csv = AccuracyCsv(rows, about);
  const auto charts =
      AccuracyCharts(rows, bc.name + " | " + machine + " | " + std::to_string(options.poses) +
                               " poses, thread CPU");
  WriteFileAtomic(out / "accuracy.csv", csv);
  WriteFileAtomic(out / "accuracy-table.json", AccuracyTableJson(rows, bc.name, machine, options));
  for (const auto& [file, png] : charts) WriteFileAtomic(out / file, png);
  std::cout << csv;
  std::cerr << "bench: wrote accuracy.csv, accuracy-table.json and the charts to " << args.out
            << "\n";
}

void RunBenchCommand(const BenchArgs& args, bool voxels_given) {
  PrepareOutputDir(args.out);
  const BenchCase bc = LoadBenchCase(args.case_dir, args.synthetic, args.seed, args.axis);
  const std::string machine = MachineLine();
  std::cerr << "bench: case " << bc.name << " (" << bc.lower_L->num_triangles() << " lower / "
            << bc.upper_U->num_triangles() << " upper triangles), axis (" << bc.axis_L.transpose()
            << "), " << machine << "\n";
  const std::filesystem::path out(args.out);
  const std::string subtitle = bc.name + " | " + machine +
                               " | query: thread CPU time, median of jittered poses (fastest of " +
                               std::to_string(args.rounds) + " rounds)";

  if (args.haptic) {
    HapticOptions options;
    if (voxels_given) options.voxels_mm = args.voxels;
    GuardBenchMemory(bc, options.voxels_mm, args);
    options.periods_us = args.periods;
    options.seconds = args.seconds;
    options.seed = args.seed;
    options.delta_mm = args.delta_mm;
    options.fcl = !args.no_fcl;
    options.log = &std::cerr;
    const std::vector<HapticRow> rows = RunHaptic(bc, options);
    WriteFileAtomic(out / "haptic.csv", HapticCsv(rows));
    for (const auto& [file, png] : HapticCharts(
             rows, bc.name + " | " + machine + " | wall-clock latency, busy-wait release")) {
      WriteFileAtomic(out / file, png);
    }
    std::cout << HapticCsv(rows);
    std::cerr << "bench: wrote " << (out / "haptic.csv").string() << " and the haptic charts\n";
    return;
  }

  GuardBenchMemory(bc, args.voxels, args);
  BenchOptions options;
  options.voxels_mm = args.voxels;
  if (!args.offsets.empty()) options.offsets_mm = args.offsets;
  options.reps = args.reps;
  options.rounds = args.rounds;
  options.seed = args.seed;
  options.delta_mm = args.delta_mm;
  options.jitter_deg = args.jitter_deg;
  options.jitter_mm = args.jitter_mm;
  options.fcl = !args.no_fcl;
  options.openvdb = !args.no_openvdb;
  options.log = &std::cerr;
  if (options.fcl && !FclPeer::Available()) {
    std::cerr << "occlude: warning: the FCL rows are missing: " << FclPeer::Unavailable() << "\n";
  }
  if (options.openvdb && !OpenVdbPeer::Available()) {
    std::cerr << "occlude: warning: the OpenVDB rows are missing: " << OpenVdbPeer::Unavailable()
              << "\n";
  }
  const std::vector<BenchRow> rows = RunBench(bc, options);
  const std::string summary =
      "case " + bc.name + "; " + machine + "; " + std::to_string(options.rounds) + " rounds of " +
      std::to_string(options.reps) +
      " jittered poses per offset, a row's median the fastest round's\n" + BenchSummary(rows);
  WriteFileAtomic(out / "bench.csv", BenchCsv(rows));
  WriteFileAtomic(out / "bench-summary.txt", summary);
  for (const auto& [file, png] : BenchCharts(rows, subtitle)) WriteFileAtomic(out / file, png);
  std::cout << summary;
  std::cerr << "bench: wrote " << (out / "bench.csv").string()
            << ", bench-summary.txt and the charts\n";
}

// The jaw pair and the occlusal-axis sweep's options (shared by the modes); returns the
// --voxel option (the modes have their own defaults when it is not given).
CLI::Option* AddCaseAndSweepOptions(CLI::App* cmd, BenchArgs* args) {
  auto* case_opt =
      cmd->add_option("--case", args->case_dir, "Case folder with upper.stl and lower.stl");
  auto* synth_opt = cmd->add_option("--synthetic", args->synthetic,
                                    "Use the generated jaw pair with this many triangles per jaw");
  case_opt->excludes(synth_opt);
  synth_opt->excludes(case_opt);
  auto* voxel_opt =
      cmd->add_option("--voxel", args->voxels,
                      "Voxel sizes, mm (comma separated; --paper: 10,5,1,0.8,0.4,0.2,0.1)")
          ->delimiter(',')
          ->capture_default_str()
          ->check(PositiveMm());
  cmd->add_option("--offsets", args->offsets,
                  "Offsets along the axis, mm (default 5 ... -0.2; --paper: 40 ... -0.2)")
      ->delimiter(',');
  cmd->add_option("--reps", args->reps,
                  "Jittered poses per offset (--paper: 9; --accuracy: timed queries per pose, 3)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--rounds", args->rounds,
                  "Whole sweeps; each row keeps the fastest round's median and the slowest query")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  cmd->add_option("--seed", args->seed, "Seed of the jitter, the trajectory and the synthetic pair")
      ->capture_default_str();
  cmd->add_option("--delta", args->delta_mm,
                  "Contact band, mm (--paper: 0, the paper's overlap test)")
      ->capture_default_str()
      ->check(BandMm());
  cmd->add_option("--axis", args->axis, "Occlusal axis: auto, x, y, z, -x, -y, -z")
      ->capture_default_str();
  cmd->add_option("--jitter-deg", args->jitter_deg, "Rotation jitter per pose, degrees")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--jitter-mm", args->jitter_mm, "Translation jitter per pose, mm")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 5.0));
  cmd->add_flag("--no-fcl", args->no_fcl, "Skip the FCL peer");
  cmd->add_flag("--no-openvdb", args->no_openvdb,
                "Skip the OpenVDB peer (the sweep's level-set build and samples)");
  return voxel_opt;
}

// --haptic's options, --out and the memory budget.
void AddHapticAndOutputOptions(CLI::App* cmd, BenchArgs* args) {
  cmd->add_flag("--haptic", args->haptic,
                "Replay a seeded trajectory at fixed periods instead (default voxel 0.2 mm)");
  cmd->add_option("--periods", args->periods, "Haptic tick periods, us")
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::Range(1.0, 1e6));
  cmd->add_option("--seconds", args->seconds, "Haptic trajectory duration, s")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 600.0));
  cmd->add_option("--out", args->out, "Output folder")->required();
  AddMemoryBudgetOption(cmd, &args->memory_budget_mb);
}

// --paper's and --accuracy's options.
void AddPaperAndAccuracyOptions(CLI::App* cmd, BenchArgs* args) {
  auto* paper_opt =
      cmd->add_flag("--paper", args->paper,
                    "Reproduce the paper's figures (voxels, build, sphere volume, query rate)");
  auto* accuracy_opt = cmd->add_flag("--accuracy", args->accuracy,
                                     "Speed against accuracy of every method (exact ground truth)");
  paper_opt->excludes(accuracy_opt);
  accuracy_opt->excludes(paper_opt);
  auto* mesh_opt =
      cmd->add_option("--mesh", args->mesh, "--paper on one mesh file (no query-rate figure)");
  mesh_opt->excludes(cmd->get_option("--case"))->excludes(cmd->get_option("--synthetic"));
  cmd->add_flag("--no-sweep", args->no_sweep, "--paper: skip Fig. 10 (the query-rate sweep)");
  cmd->add_option("--sweep-voxel", args->sweep_voxels, "--paper: voxel sizes of Fig. 10, mm")
      ->delimiter(',')
      ->capture_default_str()
      ->check(PositiveMm());
  cmd->add_option("--poses", args->poses, "--accuracy: seeded poses about the bite")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--offset-range", args->offset_range,
                  "--accuracy: offsets along the axis, mm (lo,hi)")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  cmd->add_option("--truth-spacing", args->truth_spacing,
                  "--accuracy: spacing of the ground-truth upper samples, mm")
      ->capture_default_str()
      ->check(MmBetween(0.001, true, 1.0, "a spacing in mm between 0.001 and 1"));
}

// The checks across options, then the mode.
void RunBenchMode(const BenchArgs& args, const Given& given) {
  if (!args.mesh.empty() && !args.paper) {
    throw UserError("--mesh: only with --paper (the other modes need a jaw pair: --case DIR)");
  }
  if (args.case_dir.empty() && args.synthetic == 0 && args.mesh.empty()) {
    throw UserError(std::string("bench: give --case DIR (with upper.stl and lower.stl)") +
                    (args.paper ? ", --mesh FILE" : "") + " or --synthetic N");
  }
  if (args.offset_range[0] >= args.offset_range[1]) {
    throw UserError("--offset-range: give lo,hi with lo < hi (mm), e.g. -0.2,1");
  }
  if (args.paper) return RunPaperCommand(args, given);
  if (args.accuracy) return RunAccuracyCommand(args, given);
  RunBenchCommand(args, given.voxels);
}

}  // namespace

void AddBenchCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "bench",
      "Time IST queries and the oracle against FCL and OpenVDB along the occlusal axis (CSV + PNG "
      "charts)");
  auto args = std::make_shared<BenchArgs>();
  auto* voxel_opt = AddCaseAndSweepOptions(cmd, args.get());
  AddHapticAndOutputOptions(cmd, args.get());
  AddPaperAndAccuracyOptions(cmd, args.get());
  auto* reps_opt = cmd->get_option("--reps");
  auto* offsets_opt = cmd->get_option("--offsets");
  auto* delta_opt = cmd->get_option("--delta");
  cmd->callback([args, voxel_opt, reps_opt, offsets_opt, delta_opt] {
    RunBenchMode(*args, {voxel_opt->count() > 0, reps_opt->count() > 0, offsets_opt->count() > 0,
                         delta_opt->count() > 0});
  });
}

}  // namespace occlude::app
