// `occlude validate`: every solver from seeded perturbed starts of a case with a known bite;
// CSV per run, summary per solver and magnitude, stability and error charts (validate.h).
#include <iostream>
#include <memory>
#include <sstream>

#include "base/output_files.h"
#include "base/user_error.h"
#include "bench/bench_inputs.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "session/jaw_pair.h"
#include "validate/validate.h"
#include "validate/validate_global.h"

namespace occlude::app {
namespace {

struct ValidateArgs {
  std::string case_dir;
  std::size_t synthetic = 0;
  std::vector<std::string> solvers = {"ceres", "coarse-to-fine", "nlopt-local", "nlopt-global"};
  int starts = 20;
  std::string magnitudes = "1:2,2:3,5:10";
  std::uint32_t seed = 1;
  std::vector<double> voxels = {0.8, 0.4};
  bool exact = false;
  int threads = 0;
  int solver_starts = 4;
  std::string nlopt_local = planner::ToString(planner::PlanRequest{}.nlopt_local);
  double band_mm = 0.1;
  double max_penetration_mm = 0.05;
  std::string out;
  bool global = false;
  double scan_step_mm = planner::GlobalScanSettings{}.sagittal_step_mm;
  std::vector<int> basins = {planner::GlobalScanSettings{}.max_basins,
                             planner::GlobalScanSettings{}.max_refined};
  std::vector<std::string> kinds = ValidateOptions{}.global_kinds;
  double cusp_period_mm = ValidateOptions{}.cusp_period_mm;
  std::string clinical;       // --clinical FILE
  bool solver_given = false;  // --solver on the command line
};

// `--global`: the solvers in global scope from near, sagittal and apart starts
// (validate/validate_global.h); the default solver unless --solver names others.
void RunGlobalValidateCommand(const ValidateArgs& args, ValidateOptions options,
                              const JawPair& jaws, const std::string& machine) {
  if (!args.solver_given) options.solvers = {planner::PlanRequest{}.solver};
  if (args.basins.size() != 2)
    throw UserError("--basins: give two counts, scanned,refined (e.g. 12,6)");
  options.global_scan.sagittal_step_mm = args.scan_step_mm;
  options.global_scan.max_basins = args.basins[0];
  options.global_scan.max_refined = args.basins[1];
  options.global_kinds = args.kinds;
  options.cusp_period_mm = args.cusp_period_mm;
  std::cerr << "validate --global: case " << jaws.name << ", " << options.solvers.size()
            << " solver(s) x " << options.global_kinds.size() << " start kinds x " << options.starts
            << " starts; " << machine << "\n";
  const GlobalValidateResult result = RunGlobalValidation(jaws, options);
  const std::filesystem::path out(args.out);
  const std::string summary = GlobalValidateSummaryText(result, options, machine);
  const auto charts =
      GlobalValidateCharts(result, options, jaws.name + " | " + machine + " | one core per run");
  std::vector<std::pair<std::string, std::string>> files = {
      {"validate.csv", GlobalValidateCsv(result)},
      {"validate-summary.csv", GlobalValidateSummaryCsv(result)},
      {"validate-summary.txt", summary}};
  files.insert(files.end(), charts.begin(), charts.end());
  for (const auto& [file, bytes] : files) WriteFileAtomic(out / file, bytes);
  std::cout << summary;
  std::cerr << "validate: wrote " << (out / "validate.csv").string()
            << ", the summaries and stability.png\n";
}

void RunValidateCommand(const ValidateArgs& args) {
  ValidateOptions options;
  options.solvers.clear();
  for (const std::string& name : args.solvers) {
    try {
      options.solvers.push_back(planner::SolverKindFromName(name));
    } catch (const std::invalid_argument& e) {
      throw UserError(std::string("--solver: ") + e.what());
    }
  }
  options.magnitudes = ParseMagnitudes(args.magnitudes);
  options.starts = args.starts;
  options.seed = args.seed;
  options.voxels_mm = args.voxels;
  options.exact_last = args.exact;
  options.threads = args.threads;
  options.solver_starts = args.solver_starts;
  try {
    options.nlopt_local = planner::NloptLocalMethodFromName(args.nlopt_local);
  } catch (const std::invalid_argument& e) {
    throw UserError(std::string("--nlopt-local: ") + e.what());
  }
  options.contact_band_mm = args.band_mm;
  options.max_penetration_mm = args.max_penetration_mm;
  options.log = &std::cerr;
  if (!args.clinical.empty()) options.clinical = LoadClinicalTargets(args.clinical);
  PrepareOutputDir(args.out);
  const JawPair jaws = args.case_dir.empty() ? SyntheticJawPair(args.synthetic, args.seed)
                                             : LoadCaseFolder(args.case_dir);
  const std::string machine = MachineLine();
  if (args.global) return RunGlobalValidateCommand(args, options, jaws, machine);
  std::cerr << "validate: case " << jaws.name << ", " << options.solvers.size() << " solvers x "
            << options.magnitudes.size() << " magnitudes x " << options.starts << " starts; "
            << machine << "\n";
  const ValidateResult result = RunValidation(jaws, options);
  const std::filesystem::path out(args.out);
  const std::string summary = ValidateSummaryText(result, options, machine);
  const auto charts =
      ValidateCharts(result, options, jaws.name + " | " + machine + " | one core per run");
  WriteFileAtomic(out / "validate.csv", ValidateCsv(result));
  WriteFileAtomic(out / "validate-summary.csv", ValidateSummaryCsv(result));
  WriteFileAtomic(out / "validate-summary.txt", summary);
  WriteFileAtomic(out / "reference-path.csv", ReferencePathCsv(result));
  for (const auto& [file, png] : charts) WriteFileAtomic(out / file, png);
  std::cout << summary;
  std::cerr << "validate: wrote " << (out / "validate.csv").string()
            << ", the summaries and the charts\n";
}

}  // namespace

void AddValidateCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "validate",
      "Run every solver from seeded perturbed starts of a known bite; CSV, summary and charts");
  auto args = std::make_shared<ValidateArgs>();
  auto* case_opt = cmd->add_option("--case", args->case_dir,
                                   "Case folder with upper.stl and lower.stl at the bite");
  auto* synth_opt = cmd->add_option("--synthetic", args->synthetic,
                                    "Use the generated jaw pair with this many triangles per jaw");
  case_opt->excludes(synth_opt);
  synth_opt->excludes(case_opt);
  cmd->add_option("--scan-step", args->scan_step_mm, "With --global: the scan's sagittal step, mm")
      ->capture_default_str()
      ->check(MmBetween(0.1, false, 15.0, "a step in mm between 0.1 and 15"));
  cmd->add_option("--basins", args->basins,
                  "With --global: scan basins through the coarse stage, and of those refined")
      ->delimiter(',')
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  auto* kinds_opt =
      cmd->add_option(
             "--kinds", args->kinds,
             "With --global: the start kinds (comma separated): near, sagittal, apart, cusp")
          ->delimiter(',')
          ->capture_default_str()
          ->check(CLI::IsMember(GlobalStartKinds()));
  auto* cusp_opt =
      cmd->add_option(
             "--cusp-period", args->cusp_period_mm,
             "With --global: how far the cusp kind's starts are shifted along the arch, mm")
          ->capture_default_str()
          ->check(MmBetween(0.5, false, 20.0, "a shift in mm between 0.5 and 20"));
  auto* clinical_opt =
      cmd->add_option("--clinical", args->clinical,
                      "With --global: rank the seats by the [clinical] table of this TOML file (a "
                      "case config or a file with only that table) instead of the default ranking");
  auto* solver_opt =
      cmd->add_option("--solver", args->solvers,
                      "Solvers (comma separated): ceres, coarse-to-fine, nlopt-local, nlopt-global")
          ->delimiter(',')
          ->capture_default_str();
  cmd->add_option("--starts", args->starts,
                  "Perturbed starts per magnitude (with --global: per start kind)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--magnitudes", args->magnitudes,
                  "Perturbation magnitudes MM:DEG (comma separated; 0:0 = closing run)")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Seed of the perturbations (and of the synthetic pair)")
      ->capture_default_str();
  cmd->add_option("--voxels", args->voxels, "Oracle schedule, coarse first, mm (comma separated)")
      ->delimiter(',')
      ->capture_default_str()
      ->check(MmBetween(0.02, true, 5.0, "a voxel size in mm between 0.02 and 5"));
  cmd->add_flag("--exact", args->exact, "Add a last stage on exact triangle distances");
  cmd->add_option("--threads", args->threads, "Runs in parallel (each on one core); 0 = all cores")
      ->capture_default_str()
      ->check(CLI::Range(0, 256));
  cmd->add_option("--solver-starts", args->solver_starts,
                  "Internal starts of coarse-to-fine and nlopt-global")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  cmd->add_option("--nlopt-local", args->nlopt_local,
                  "NLopt local method: cobyla, auglag-bobyqa, auglag-sbplx")
      ->capture_default_str();
  cmd->add_option("--band", args->band_mm, "Contact band, mm")
      ->capture_default_str()
      ->check(BandMm());
  cmd->add_option("--max-penetration", args->max_penetration_mm, "Allowed penetration, mm")
      ->capture_default_str()
      ->check(MmBetween(0.0, true, 5.0, "a depth in mm between 0 and 5"));
  cmd->add_option("--out", args->out, "Output folder")->required();
  cmd->add_flag("--global", args->global,
                "Global scope: the solvers from near, sagittal and apart starts (--starts per "
                "kind), scored against the seat of the reference too");
  cmd->callback([args, solver_opt, kinds_opt, cusp_opt, clinical_opt] {
    args->solver_given = solver_opt->count() > 0;
    for (const CLI::Option* global_only : {kinds_opt, cusp_opt, clinical_opt}) {
      if (!args->global && global_only->count() > 0)
        throw UserError("validate: " + global_only->get_name() +
                        " applies to --global only; "
                        "add --global or leave it out");
    }
    if (args->case_dir.empty() && args->synthetic == 0) {
      throw UserError(
          "validate: give --case DIR (with upper.stl and lower.stl at the bite) or --synthetic N");
    }
    RunValidateCommand(*args);
  });
}

}  // namespace occlude::app
