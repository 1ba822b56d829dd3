// `occlude bench`: the paper's query-rate experiment on a jaw pair, with FCL
// side by side (CSV + PNG charts), and `--haptic`, the fixed-period loop.
#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "bench.h"
#include "commands.h"
#include "fcl_peer.h"
#include "memory_guard.h"
#include "occlude/collision/oracle.h"
#include "occlude/io/mesh_io.h"
#include "output_files.h"
#include "synthetic_case.h"

namespace occlude::app {
namespace {

struct BenchArgs {
  std::string case_dir;
  std::size_t synthetic = 0;
  std::vector<double> voxels = {0.8, 0.4, 0.2, 0.1};
  std::vector<double> offsets;
  int reps = 15;
  std::uint32_t seed = 1;
  double delta_mm = 0.1;
  std::string axis = "auto";
  double jitter_deg = 0.2, jitter_mm = 0.05;
  bool no_fcl = false;
  bool haptic = false;
  std::vector<double> periods = {1000.0, 100.0};
  double seconds = 2.0;
  std::string out;
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
void GuardBenchMemory(const BenchCase& bc, const std::vector<double>& voxels, const BenchArgs& args) {
  if (voxels.empty()) return;
  const double finest = *std::min_element(voxels.begin(), voxels.end());
  std::ostringstream subject;
  subject << "--voxel " << finest;
  CheckMemory({subject.str(), "the contact oracle", "the finest --voxel", 5.0, "decimate the meshes",
               {ExtentOf(JawName(args, "lower"), *bc.lower_L), ExtentOf(JawName(args, "upper"), *bc.upper_U)}},
              [&](double voxel_mm) {
                collision::OracleOptions options;
                options.voxel_size_mm = voxel_mm;
                options.sample_spacing_mm = std::min(0.3, 1.5 * voxel_mm);
                return collision::EstimateOracleMemory(*bc.lower_L, *bc.upper_U, options);
              },
              finest, ResolveMemoryBudget(args.memory_budget_mb));
}

// "auto" (the lower-to-upper direction, snapped to a coordinate axis within
// 30 degrees), or x, y, z with an optional sign.
Eigen::Vector3d BenchAxis(const std::string& text, const io::TriangleMesh& lower_L,
                          const io::TriangleMesh& upper_L) {
  if (text == "auto") {
    const Eigen::Vector3d a =
        collision::EstimateArchFrame(lower_L, upper_L).occlusal_L.normalized();
    Eigen::Index i = 0;
    a.cwiseAbs().maxCoeff(&i);
    if (std::abs(a[i]) > std::cos(30.0 * 3.14159265358979 / 180.0)) {
      return Eigen::Vector3d::Unit(i) * (a[i] > 0 ? 1.0 : -1.0);
    }
    return a;
  }
  const bool negative = !text.empty() && text[0] == '-';
  const std::string name = (negative || (!text.empty() && text[0] == '+')) ? text.substr(1) : text;
  if (name != "x" && name != "y" && name != "z") {
    throw UserError("--axis: '" + text + "' is not an axis (use auto, x, y, z, -x, -y or -z)");
  }
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(name[0] - 'x');
  return negative ? Eigen::Vector3d(-axis) : axis;
}

std::shared_ptr<const io::TriangleMesh> LoadCaseMesh(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) {
    throw UserError(file.string() +
                    ": not found (--case needs a folder with upper.stl and lower.stl)");
  }
  try {
    io::LoadReport report;
    auto mesh = std::make_shared<io::TriangleMesh>(io::LoadMesh(file, {}, &report));
    for (const auto& w : report.warnings) std::cerr << "occlude: warning: " << w << "\n";
    return mesh;
  } catch (const io::MeshError& e) {
    throw UserError(e.what());
  }
}

std::string ReadFirstLine(const char* file, const std::string& prefix) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (prefix.empty() || line.rfind(prefix, 0) == 0) return line;
  }
  return "";
}

// The machine, stated with every figure: cores, CPU model, load at the start.
std::string MachineLine() {
  std::string cpu = ReadFirstLine("/proc/cpuinfo", "model name");
  const auto colon = cpu.find(':');
  cpu = colon == std::string::npos ? std::string("unknown CPU") : cpu.substr(colon + 2);
  std::istringstream load(ReadFirstLine("/proc/loadavg", ""));
  std::string load1;
  load >> load1;
  return std::to_string(std::thread::hardware_concurrency()) + " cores (" + cpu + "), load " +
         (load1.empty() ? "?" : load1) + " at start";
}

void RunBenchCommand(const BenchArgs& args, bool voxels_given) {
  PrepareOutputDir(args.out);
  BenchCase bc;
  if (!args.case_dir.empty()) {
    const std::filesystem::path dir(args.case_dir);
    if (!std::filesystem::is_directory(dir)) {
      throw UserError("--case: '" + args.case_dir +
                      "' is not a folder (it must hold upper.stl and lower.stl)");
    }
    bc.name =
        dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
    bc.lower_L = LoadCaseMesh(dir / "lower.stl");
    bc.upper_U = LoadCaseMesh(dir / "upper.stl");  // given in L at the bite: U = L
    bc.axis_L = BenchAxis(args.axis, *bc.lower_L, *bc.upper_U);
  } else {
    io::SyntheticJawOptions options;
    options.triangles_per_jaw = args.synthetic;
    options.seed = args.seed;
    const io::SyntheticJawPair jaws = MakeSyntheticOrExplain(options);
    bc.name = "synthetic-" + std::to_string(args.synthetic);
    bc.lower_L = std::make_shared<io::TriangleMesh>(jaws.lower_L);
    bc.upper_U = std::make_shared<io::TriangleMesh>(jaws.upper_U);
    bc.X_LU_ref = jaws.X_LU;
    bc.axis_L = args.axis == "auto"
                    ? jaws.occlusal_axis_L
                    : BenchAxis(args.axis, *bc.lower_L, bc.upper_U->Transformed(bc.X_LU_ref));
  }
  const std::string machine = MachineLine();
  std::cerr << "bench: case " << bc.name << " (" << bc.lower_L->num_triangles() << " lower / "
            << bc.upper_U->num_triangles() << " upper triangles), axis (" << bc.axis_L.transpose()
            << "), " << machine << "\n";
  const std::filesystem::path out(args.out);
  const std::string subtitle =
      bc.name + " | " + machine + " | query: thread CPU time, median of jittered poses";

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
  options.seed = args.seed;
  options.delta_mm = args.delta_mm;
  options.jitter_deg = args.jitter_deg;
  options.jitter_mm = args.jitter_mm;
  options.fcl = !args.no_fcl;
  options.log = &std::cerr;
  if (options.fcl && !FclPeer::Available()) {
    std::cerr << "occlude: warning: built without FCL (libfcl-dev): the FCL rows are missing\n";
  }
  const std::vector<BenchRow> rows = RunBench(bc, options);
  const std::string summary = "case " + bc.name + "; " + machine + "\n" + BenchSummary(rows);
  WriteFileAtomic(out / "bench.csv", BenchCsv(rows));
  WriteFileAtomic(out / "bench-summary.txt", summary);
  for (const auto& [file, png] : BenchCharts(rows, subtitle)) WriteFileAtomic(out / file, png);
  std::cout << summary;
  std::cerr << "bench: wrote " << (out / "bench.csv").string()
            << ", bench-summary.txt and the charts\n";
}

}  // namespace

void AddBenchCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "bench",
      "Time IST queries and the oracle against FCL along the occlusal axis (CSV + PNG charts)");
  auto args = std::make_shared<BenchArgs>();
  auto* case_opt =
      cmd->add_option("--case", args->case_dir, "Case folder with upper.stl and lower.stl");
  auto* synth_opt = cmd->add_option("--synthetic", args->synthetic,
                                    "Use the generated jaw pair with this many triangles per jaw");
  case_opt->excludes(synth_opt);
  synth_opt->excludes(case_opt);
  auto* voxel_opt = cmd->add_option("--voxel", args->voxels, "Voxel sizes, mm (comma separated)")
                        ->delimiter(',')
                        ->capture_default_str()
                        ->check(PositiveMm());
  cmd->add_option("--offsets", args->offsets, "Offsets along the axis, mm (default 5 ... -0.2)")
      ->delimiter(',');
  cmd->add_option("--reps", args->reps, "Jittered poses per offset")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--seed", args->seed, "Seed of the jitter, the trajectory and the synthetic pair")
      ->capture_default_str();
  cmd->add_option("--delta", args->delta_mm, "Contact band, mm")
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
  cmd->callback([cmd, args, voxel_opt] {
    if (args->case_dir.empty() && args->synthetic == 0) {
      throw UserError("bench: give --case DIR (with upper.stl and lower.stl) or --synthetic N");
    }
    (void)cmd;
    RunBenchCommand(*args, voxel_opt->count() > 0);
  });
}

}  // namespace occlude::app
