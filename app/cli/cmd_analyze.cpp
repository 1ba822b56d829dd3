// `occlude analyze CONFIG | --case DIR [--pose pose.json] [--landmarks FILE] --out DIR`: the arch
// analysis of both jaws (teeth, landmarks with confidences, given landmarks overriding detected
// ones) and the clinical relationships at one pose, as analysis.json and landmarks.png
// (report/analysis_document.h). The pose: --pose, else the config's start pose, else (--case)
// the registered bite. Landmarks: --landmarks, else the config's [landmarks] file, else
// (--case) DIR/landmarks.csv when present. A jaw on which no tooth is found is a warning; the
// rest is still written.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "base/output_files.h"
#include "base/text_format.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "cli/cache_options.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "config/case_config.h"
#include "config/case_output.h"
#include "config/pose_file.h"
#include "report/analysis_document.h"
#include "session/case_analysis.h"
#include "session/case_session.h"
#include "session/jaw_pair.h"
#include "session/oracle_cache.h"

namespace occlude::app {
namespace {

struct AnalyzeArgs {
  std::string config;
  std::string case_dir;
  std::string pose;
  std::string landmarks;
  CacheArgs cache;
  std::string out;
};

// The --pose file, read before any work (given = false without one).
struct PoseOption {
  bool given = false;
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
  std::string source;
};

PoseOption ReadPoseOption(const std::string& pose) {
  PoseOption p;
  if (pose.empty()) return p;
  p.given = true;
  p.X_LU = ReadPoseFile(pose);
  p.source = "pose file " + std::filesystem::absolute(pose).lexically_normal().string();
  return p;
}

// The case folder's landmark file: --landmarks, else DIR/landmarks.csv when present.
std::optional<std::filesystem::path> CaseLandmarks(const AnalyzeArgs& args) {
  if (!args.landmarks.empty()) return std::filesystem::absolute(args.landmarks).lexically_normal();
  const std::filesystem::path in_case = std::filesystem::path(args.case_dir) / "landmarks.csv";
  std::error_code ec;
  if (std::filesystem::is_regular_file(in_case, ec)) return in_case;
  return std::nullopt;
}

void Report(const AnalysisInputs& in, const AnalysisFiles& files, const std::filesystem::path& out,
            double start) {
  for (const std::string& w : files.warnings) std::cerr << "occlude: warning: " << w << "\n";
  const CaseAnalysis& a = *in.analysis;
  const analysis::Relationships& r = files.relationships;
  const auto mm = [](const analysis::Measure& m) {
    return m.mm ? Fixed(*m.mm, 2) + " mm" : std::string("not found");
  };
  std::cout << in.case_name << ": " << a.lower_L.teeth.size() << " lower and "
            << a.upper_U.teeth.size() << " upper teeth, "
            << a.lower_L.landmarks.size() + a.upper_U.landmarks.size() << " landmarks"
            << (a.has_given_landmarks ? " (given ones from " + in.landmarks_source + ")" : "")
            << "; overjet " << mm(r.overjet) << ", overbite " << mm(r.overbite) << ", midline "
            << mm(r.midline_deviation) << ", molar R/L " << mm(r.molar[0].offset) << " / "
            << mm(r.molar[1].offset) << "; analysis in " << (out / "analysis.json").string() << " ("
            << Fixed(NowSeconds() - start, 2) << " s)\n";
}

void Write(const AnalysisInputs& in, const std::filesystem::path& out, double start) {
  const AnalysisFiles files = MakeAnalysisFiles(in);
  for (const auto& [name, content] : files.files) WriteFileAtomic(out / name, content);
  Report(in, files, out, start);
}

void AnalyzeConfig(const AnalyzeArgs& args, double start) {
  const CaseConfig config = LoadCaseConfigWithOptions(args.config, args.landmarks, args.cache);
  const PoseOption pose = ReadPoseOption(args.pose);
  const std::filesystem::path out = PrepareCaseOutput(config, args.out);
  CaseSession session(config);
  AnalysisInputs in;
  in.case_name = config.name;
  in.pose_source = pose.given ? pose.source : "start pose of the config";
  in.landmarks_source = config.landmarks_file ? config.landmarks_file->string() : "";
  in.jaws = &session.jaws();
  in.analysis = &session.Analysis();
  in.X_LU = pose.given ? pose.X_LU : session.ConfigStartPose();
  in.image_width_px = config.report.image_width_px;
  Write(in, out, start);
}

void AnalyzeCaseFolder(const AnalyzeArgs& args, double start) {
  if (args.out.empty()) {
    throw UserError("--out: give the output folder (with --case there is no config to name one)");
  }
  const PoseOption pose = ReadPoseOption(args.pose);
  const std::optional<std::filesystem::path> landmarks = CaseLandmarks(args);
  const std::vector<io::Landmark> given =
      landmarks ? ReadGivenLandmarks(*landmarks) : std::vector<io::Landmark>{};
  const JawPair pair = LoadCaseFolder(args.case_dir);
  PrepareOutputDir(args.out);
  OracleCache cache(OracleCacheSettings{!args.cache.off, args.cache.folder}, &std::cerr);
  const CaseAnalysis analysis = AnalyzeCase(pair, given, &cache);
  AnalysisInputs in;
  in.case_name = pair.name;
  in.pose_source = pose.given ? pose.source : "the registered bite (as scanned)";
  in.landmarks_source = landmarks ? landmarks->string() : "";
  in.jaws = &pair;
  in.analysis = &analysis;
  in.X_LU = pose.given ? pose.X_LU : pair.X_LU_ref;
  Write(in, args.out, start);
}

void RunAnalyze(const AnalyzeArgs& args) {
  const double start = NowSeconds();
  if (args.config.empty() == args.case_dir.empty()) {
    throw UserError(
        "analyze: give either a case config (CONFIG) or a case folder (--case DIR), not " +
        std::string(args.config.empty() ? "neither" : "both"));
  }
  if (args.config.empty()) {
    AnalyzeCaseFolder(args, start);
  } else {
    AnalyzeConfig(args, start);
  }
}

}  // namespace

void AddAnalyzeCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "analyze",
      "Detect the teeth and landmarks of both jaws and measure the clinical relationships at a "
      "pose: analysis.json and landmarks.png");
  auto args = std::make_shared<AnalyzeArgs>();
  cmd->add_option("config", args->config, "Case config file (TOML; see examples/)");
  cmd->add_option("--case", args->case_dir,
                  "Case folder (upper.stl and lower.stl at the registered bite; landmarks.csv "
                  "is used when present) instead of a config");
  cmd->add_option("--pose", args->pose,
                  "Pose file (JSON with a 4x4 \"X_LU\"); default: the config's start pose, or "
                  "the registered bite of --case");
  AddLandmarksOption(cmd, &args->landmarks);
  AddCacheOptions(cmd, &args->cache);
  cmd->add_option("--out", args->out,
                  "Output folder; default: [output] folder of the config (required with --case)");
  cmd->callback([args] { RunAnalyze(*args); });
}

}  // namespace occlude::app
