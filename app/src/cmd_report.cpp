// `occlude report CASE.toml [--pose FILE] [--out DIR]`: evaluates one pose of a
// case (the config's start pose, or a pose file) and writes what a surgeon
// attaches to a plan: report.html (self-contained), the contact maps and views
// as PNG, metrics.json, pose.json and the upper jaw at the pose as STL.
// Everything is computed before the first file is written, and every file is
// written atomically, so a failed run leaves no half-written output.
#include <iostream>
#include <memory>
#include <sstream>

#include "case_config.h"
#include "commands.h"
#include "jaw_checks.h"
#include "memory_guard.h"
#include "occlude/io/mesh_io.h"
#include "output_files.h"
#include "pose_file.h"
#include "report_analysis.h"
#include "report_document.h"
#include "report_images.h"
#include "timing.h"

namespace occlude::app {
namespace {

struct ReportArgs {
  std::string config;
  std::string pose;
  std::string out;
  double memory_budget_mb = 0;
};

// Reports each finished step that took over a second on stderr.
class StepClock {
 public:
  void Start(const std::string& step) {
    Finish();
    step_ = step;
    t0_ = NowSeconds();
  }
  void Finish() {
    if (!step_.empty() && NowSeconds() - t0_ > 1.0) {
      std::ostringstream s;
      s.precision(2);
      s << std::fixed << "occlude: " << step_ << " (" << NowSeconds() - t0_ << " s)\n";
      std::cerr << s.str() << std::flush;
    }
    step_.clear();
  }

 private:
  std::string step_;
  double t0_ = 0.0;
};

// The files of a jaw for messages.
std::string JawName(const CaseConfig& config, const std::optional<JawFiles>& jaw) {
  if (!jaw) return config.file.string() + " [synthetic]";
  std::vector<std::string> files;
  for (const auto& f : jaw->files) files.push_back(f.string());
  return JawFilesName(files);
}

void RunReport(const ReportArgs& args) {
  const double start = NowSeconds();
  const CaseConfig config = LoadCaseConfig(args.config);
  std::filesystem::path out;
  if (!args.out.empty()) {
    out = args.out;
  } else if (config.output_dir) {
    out = *config.output_dir;
  } else {
    throw UserError(config.file.string() + ": no output folder; set [output] folder = \"...\" or pass --out");
  }
  // (A flag and a matrix rather than std::optional: GCC 12 warns falsely about the
  // optional's aligned Eigen payload being used uninitialized.)
  const bool pose_file = !args.pose.empty();
  const Eigen::Isometry3d X_LU_file = pose_file ? ReadPoseFile(args.pose) : Eigen::Isometry3d::Identity();
  try {
    PrepareOutputDir(out);
  } catch (const UserError& e) {
    if (!args.out.empty()) throw;
    throw UserError(config.file.string() + ": output.folder: " + e.what());
  }

  StepClock clock;
  clock.Start("loaded the meshes");
  double t0 = NowSeconds();
  const CaseJaws jaws = LoadCaseJaws(config);
  const double load_s = NowSeconds() - t0;
  for (const std::string& w : JawPairWarnings(*jaws.lower_L, *jaws.upper_U, Eigen::Isometry3d::Identity(),
                                              JawName(config, config.lower), JawName(config, config.upper))) {
    std::cerr << "occlude: warning: " << w << "\n";
  }
  CheckMemory({config.file.string(), "the contact oracle and the map fields", "accuracy.voxel_mm", 5.0,
               "decimate the meshes or raise accuracy.sample_spacing_mm",
               {ExtentOf(JawName(config, config.lower), *jaws.lower_L),
                ExtentOf(JawName(config, config.upper), *jaws.upper_U)}},
              [&](double voxel_mm) { return EstimateAnalysisMemory(config, jaws, voxel_mm); },
              config.VoxelSizeMm(), ResolveMemoryBudget(args.memory_budget_mb, config.memory_budget_mb));
  Eigen::Isometry3d X_LU;
  if (pose_file) {
    X_LU = X_LU_file;
  } else {
    const auto arch = CaseArchFrame(config, *jaws.lower_L, *jaws.upper_U, Eigen::Isometry3d::Identity());
    X_LU = StartPoseOf(config, UpperOcclusalCentre(*jaws.upper_U, arch.occlusal_L));
  }
  ReportAnalysis analysis = AnalyzePose(config, jaws, X_LU, [&](const std::string& step) { clock.Start(step); });
  analysis.timings_s.insert(analysis.timings_s.begin(), {"load meshes", load_s});

  clock.Start("rendered the maps and views");
  t0 = NowSeconds();
  const render::MapScale scale{config.report.map_max_mm, config.contact_band_mm,
                               config.report.map_penetration_from_mm};
  const int w = config.report.image_width_px;
  ReportInputs in;
  in.config = &config;
  in.jaws = &jaws;
  in.analysis = &analysis;
  in.pose_source = pose_file ? "pose file " + std::filesystem::absolute(args.pose).lexically_normal().string()
                             : "start pose of the config";
  in.pictures = {
      {"Lower arch, occlusal contact map", EncodePng(RenderContactMap(Arch::kLower, jaws, analysis, scale, w).image),
       "lower_map.png"},
      {"Upper arch, occlusal contact map", EncodePng(RenderContactMap(Arch::kUpper, jaws, analysis, scale, w).image),
       "upper_map.png"},
      {"Frontal view", EncodePng(RenderSideView(SideView::kFrontal, jaws, analysis, scale, w)), "frontal.png"},
      {"Right lateral view", EncodePng(RenderSideView(SideView::kLateralRight, jaws, analysis, scale, w)),
       "lateral.png"}};
  analysis.timings_s.emplace_back("render", NowSeconds() - t0);
  clock.Finish();
  analysis.timings_s.emplace_back("total before writing", NowSeconds() - start);

  const std::string metrics = MetricsJson(in);
  const std::string pose = PoseJson(in);
  const std::string html = ReportHtml(in);
  const io::TriangleMesh upper_at_pose = jaws.upper_U->Transformed(X_LU);
  for (const auto& p : in.pictures) WriteFileAtomic(out / p.file, p.png);
  WriteFileAtomic(out / "metrics.json", metrics);
  WriteFileAtomic(out / "pose.json", pose);
  try {
    io::WriteBinaryStl(upper_at_pose, out / "upper_at_pose.stl", "occlude upper jaw at the report pose (frame L, mm)");
  } catch (const io::MeshError& e) {
    throw UserError(e.what());
  }
  WriteFileAtomic(out / "report.html", html);

  const auto& o = analysis.oracle;
  std::cout << config.name << ": contact " << o.contact_area_mm2 << " mm^2 in " << analysis.spots.size()
            << " spots (band " << config.contact_band_mm << " mm), maximum penetration " << o.max_penetration_mm
            << " mm" << (o.max_penetration_mm <= config.max_penetration_mm ? "" : " (over the allowed maximum)")
            << "; report in " << (out / "report.html").string() << " (" << NowSeconds() - start << " s)\n";
}

}  // namespace

void AddReportCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("report",
                                 "Evaluate one pose of a case and write report.html, contact maps, metrics.json, "
                                 "pose.json and the upper jaw at the pose");
  auto args = std::make_shared<ReportArgs>();
  cmd->add_option("config", args->config, "Case config file (TOML; see examples/)")->required();
  cmd->add_option("--pose", args->pose, "Pose file (JSON with a 4x4 \"X_LU\"); default: the config's start pose");
  cmd->add_option("--out", args->out, "Output folder; default: [output] folder of the config");
  AddMemoryBudgetOption(cmd, &args->memory_budget_mb);
  cmd->callback([args] { RunReport(*args); });
}

}  // namespace occlude::app
