// `occlude refine CASE.toml [--out DIR] [--from-config] [--landmarks FILE]
//   [--watch [--serve [PORT] [--bind ADDR]]]`:
// interactive refinement.
// Starts from the last result in the output folder (pose.json written by propose or refine)
// or, without one or with --from-config, from the config's [start] pose; applies the
// [adjust] deltas (mm, degrees about the pivot at that pose); re-optimizes locally on the
// finest oracle with the config's locked degrees of freedom, bounds, band and penetration
// limit; writes the result, the report and refine.json; and prints what changed.
// --watch keeps the trees and repeats on every save of the config file, always from the same
// base pose (the one at launch), so editing [adjust] moves the result predictably.
// refine.hold (default "adjusted") keeps the degrees of freedom [adjust] changes at the
// adjusted value while the others settle. --serve [PORT] (with --watch) serves the live 3D
// page of the latest refinement on 127.0.0.1 (--bind ADDR: another address, with a warning)
// and pushes each one to it (cli/refine_live.h); Ctrl-C ends the watch after the refinement in
// progress, with exit code 0.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <future>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "base/json_values.h"
#include "base/output_files.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "cli/cache_options.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "cli/refine_live.h"
#include "config/case_output.h"
#include "config/plan_config.h"
#include "config/pose_file.h"
#include "report/global_proposal_report.h"
#include "report/relationships_table.h"
#include "report/report_analysis.h"
#include "report/report_viewer.h"
#include "report/report_writer.h"
#include "report/search_document.h"
#include "session/case_session.h"
#include "session/memory_guard.h"

namespace occlude::app {
namespace {

using nlohmann::json;

struct RefineArgs {
  std::string config;
  std::string out;
  std::string landmarks;
  bool from_config = false;
  bool watch = false;
  int max_refinements = 0;     ///< --watch: stop after this many (0 = until interrupted)
  double poll_seconds = 0.05;  ///< --watch: how often the config's time stamp is read (a stat)
  double memory_budget_mb = 0;
  std::vector<int> serve;  ///< --serve [PORT]: {PORT}, {0} without one; empty = not serving
  std::string bind;        ///< --bind ADDR
  CacheArgs cache;
};

json Metrics(const planner::PoseEvaluation& e) {
  return {{"contact_area_mm2", e.contact_area_mm2},
          {"contact_samples", e.contact_samples},
          {"max_penetration_mm", e.max_penetration_mm},
          {"constrained_penetration_mm", e.constrained_penetration_mm},
          {"feasible", e.feasible}};
}

std::string Triple(const Eigen::Vector3d& v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << "(" << v.x() << ", " << v.y() << ", " << v.z()
    << ")";
  return s.str();
}

// "  clinical: <measure>: before -> after" lines, base pose to result.
std::string RelationshipLines(const analysis::Relationships& before,
                              const analysis::Relationships& after) {
  std::string lines;
  for (const std::string& l : RelationshipChanges(before, after))
    lines += "  clinical: " + l + "\n";
  return lines;
}

// "tx, rz" of the set entries, or "nothing".
std::string DofList(const std::array<bool, kNumDofs>& dofs) {
  std::string out;
  for (int i = 0; i < kNumDofs; ++i) {
    if (dofs[static_cast<std::size_t>(i)])
      out += (out.empty() ? "" : ", ") + std::string(DofName(i));
  }
  return out.empty() ? "nothing" : out;
}

// Holds refine.hold's degrees of freedom at the adjusted pose: locked in the request, whose
// parameters are about the pivot carried to X_adjusted (so a held translation keeps the
// adjusted value exactly). Throws UserError when nothing would be left free.
void HoldDofs(const CaseConfig& config, const std::array<bool, kNumDofs>& held,
              const Eigen::Isometry3d& X_adjusted, const Eigen::Vector3d& pivot_L,
              planner::PlanRequest* request) {
  if (std::none_of(held.begin(), held.end(), [](bool h) { return h; })) return;
  bool any_free = false;
  for (int i = 0; i < kNumDofs; ++i) {
    request->locked[static_cast<std::size_t>(i)] |= held[static_cast<std::size_t>(i)];
    any_free |= !request->locked[static_cast<std::size_t>(i)];
  }
  if (!any_free) {
    throw UserError(config.file.string() + ": refine.hold: holding " + DofList(held) +
                    " with bounds.locked leaves no degree of freedom to settle; hold fewer "
                    "(e.g. refine.hold = [\"tx\"]) or set refine.hold = \"none\"");
  }
  request->pivot_L = X_adjusted * pivot_L;
}

// refine.hold as written: "adjusted", "none" or the list.
std::string HoldSetting(const CaseConfig& config) {
  if (config.refine.hold_adjusted) return "adjusted";
  const std::string list = DofList(config.refine.hold);
  return list == "nothing" ? "none" : "[" + list + "]";
}

// What the summary says about refine.hold.
std::string HoldSummary(const CaseConfig& config, const std::array<bool, kNumDofs>& held,
                        const planner::PoseEvaluation& after) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(3);
  const std::string what = DofList(held);
  if (what == "nothing") {
    s << "  held nothing at the adjusted value ("
      << (config.refine.hold_adjusted ? "[adjust] changes nothing" : "refine.hold = \"none\"")
      << ")\n";
    return s.str();
  }
  s << "  held " << what << " at the adjusted value (refine.hold = " << HoldSetting(config)
    << (config.refine.hold_adjusted ? ": what [adjust] changes" : "") << "); the others settled\n";
  if (!after.feasible) {
    s << "  note: the adjusted pose cannot be made feasible with " << what << " held: penetration "
      << after.constrained_penetration_mm << " mm remains, "
      << after.constrained_penetration_mm - config.max_penetration_mm << " mm over the limit "
      << config.max_penetration_mm
      << " mm; adjust less, hold fewer or set refine.hold = \"none\"\n";
  }
  return s.str();
}

// One refinement: the solve from the adjusted pose and the analysis of its result.
struct RefineOutcome {
  planner::PlanResult result;  ///< one proposal: the refined pose
  ReportAnalysis analysis;     ///< at the refined pose
  planner::PoseEvaluation before, adjusted;
  planner::PoseParameters moved;     ///< from the base, about the pivot there
  planner::PoseParameters absolute;  ///< about the pivot, relative to the pose as given
  std::array<bool, kNumDofs> held{};
  double start_s = 0, cpu_start_s = 0;  ///< wall and thread CPU clocks at the start
  const planner::Proposal& after() const { return result.proposals.front(); }
};

// Applies [adjust] to `base` and re-optimizes locally with refine.hold (nothing written).
RefineOutcome Refine(CaseSession& session, const Eigen::Isometry3d& base) {
  RefineOutcome r;
  r.start_s = NowSeconds();
  r.cpu_start_s = ThreadCpuSeconds();
  const CaseConfig& config = session.config();
  const Eigen::Isometry3d X_adjusted =
      planner::ComposePose(config.adjust, base * session.pivot_L(), base);
  planner::PlanRequest request = PlanRequestFromConfig(config, X_adjusted, session.pivot_L());
  request.solver = config.solver.name == "nlopt-local" ? planner::SolverKind::kNloptLocal
                                                       : planner::SolverKind::kCeres;
  request.num_starts = 1;
  request.max_proposals = 1;  // the one start's loops over samples use solver.threads
  r.held = RefineHeldDofs(config);
  HoldDofs(config, r.held, X_adjusted, session.pivot_L(), &request);
  // Locally, the finest oracle alone (built on first use, kept by --watch).
  const planner::OracleSchedule finest = {
      {&session.FinestOracle(), collision::AccuracyLevel::kSubVoxel}};
  r.before = planner::EvaluatePose(finest.front(), base, request);
  r.adjusted = planner::EvaluatePose(finest.front(), X_adjusted, request);
  r.result = planner::Plan(finest, request);
  r.moved = planner::DecomposePose(r.after().X_LU, base * session.pivot_L(), base);
  r.absolute =
      planner::DecomposePose(r.after().X_LU, session.pivot_L(), Eigen::Isometry3d::Identity());
  r.analysis = AnalyzePose(session, r.after().X_LU);
  return r;
}

// Writes the report of a refinement (the 3D view of the `display` meshes) and refine.json into
// `out`, and prints what changed.
void WriteRefinement(CaseSession& session, RefineOutcome& r, const Eigen::Isometry3d& base,
                     const std::string& base_source, const std::filesystem::path& out,
                     const DisplayJaws& display) {
  const CaseConfig& config = session.config();
  SearchSummary summary{"refine", base_source + " + [adjust]", &r.result, session.pivot_L(),
                        session.jaws().upper_U.get()};
  summary.analysis = &session.Analysis();
  // [clinical] kept: which targets the refined pose meets.
  const TargetsReport targets = config.clinical.from_config
                                    ? ReportTargets(config, session.Analysis(), r.after().X_LU)
                                    : TargetsReport{};
  const ReportFiles files = MakeReportFiles(
      session, r.analysis, "`occlude refine` from " + base_source, SearchJson(summary, false),
      targets.html + SearchHtml(summary), ReportView{&display, {}});
  const json refine = {
      {"base", {{"source", base_source}, {"X_LU", json::parse(MatrixJson(base.matrix()))}}},
      {"adjust",
       {{"translation_mm", Vec(config.adjust.translation_mm)},
        {"rotation_deg", Vec(config.adjust.rotation_deg)}}},
      {"result",
       {{"X_LU", json::parse(MatrixJson(r.after().X_LU.matrix()))},
        {"translation_mm", Vec(r.absolute.translation_mm)},
        {"rotation_deg", Vec(r.absolute.rotation_deg)},
        {"status", planner::ToString(r.after().status)}}},
      {"moved_from_base",
       {{"translation_mm", Vec(r.moved.translation_mm)},
        {"rotation_deg", Vec(r.moved.rotation_deg)}}},
      {"hold",
       {{"setting", HoldSetting(config)},
        {"held", DofList(r.held)},
        {"penetration_over_limit_mm",
         std::max(0.0,
                  r.after().evaluation.constrained_penetration_mm - config.max_penetration_mm)}}},
      {"before", Metrics(r.before)},
      {"adjusted", Metrics(r.adjusted)},
      {"after", Metrics(r.after().evaluation)},
      {"convention",
       "moved_from_base: about the pivot at the base pose; result: about the pivot, relative to "
       "the "
       "pose as given"}};
  WriteReportFiles(out, files, {{"refine.json", refine.dump(2) + "\n"}});

  std::cout << std::fixed << std::setprecision(3) << config.name << ": refined from " << base_source
            << " + adjust t " << Triple(config.adjust.translation_mm, 3) << " mm r "
            << Triple(config.adjust.rotation_deg, 2) << " deg\n"
            << "  moved t " << Triple(r.moved.translation_mm, 3) << " mm r "
            << Triple(r.moved.rotation_deg, 2) << " deg from the base ("
            << planner::ToString(r.after().status) << ")\n"
            << HoldSummary(config, r.held, r.after().evaluation) << "  contact "
            << std::setprecision(2) << r.before.contact_area_mm2 << " -> "
            << r.after().evaluation.contact_area_mm2 << " mm^2, max penetration "
            << std::setprecision(3) << r.before.max_penetration_mm << " -> "
            << r.after().evaluation.max_penetration_mm << " mm (constrained "
            << r.after().evaluation.constrained_penetration_mm << ", limit "
            << config.max_penetration_mm << ")\n"
            << RelationshipLines(RelationshipsAt(session.Analysis(), base),
                                 r.analysis.relationships)
            << targets.text << "  report in " << (out / "report.html").string() << " ("
            << std::setprecision(2) << NowSeconds() - r.start_s << " s wall, "
            << ThreadCpuSeconds() - r.cpu_start_s << " s CPU of this thread)\n"
            << std::flush;
}

// The numbers the live page lists beside refinement `save` (0 = the one at launch).
std::string LiveNumbers(const RefineOutcome& r, int save) {
  const planner::PoseEvaluation& after = r.after().evaluation;
  const nlohmann::ordered_json numbers = {
      {"save", save},
      {"moved t (mm)", Triple(r.moved.translation_mm, 3)},
      {"moved r (deg)", Triple(r.moved.rotation_deg, 2)},
      {"held", DofList(r.held)},
      {"contact before (mm\u00b2)", r.before.contact_area_mm2},
      {"contact after (mm\u00b2)", after.contact_area_mm2},
      {"max penetration before (mm)", r.before.max_penetration_mm},
      {"max penetration after (mm)", after.max_penetration_mm},
      {"status", planner::ToString(r.after().status)}};
  return WithRelationships(numbers.dump(), r.analysis.relationships);
}

// Set by Ctrl-C (SIGINT) while --watch runs; a signal handler reaches only static storage.
volatile std::sig_atomic_t g_interrupted = 0;
std::atomic<LiveServer*> g_live_server{nullptr};

void OnInterrupt(int) {
  g_interrupted = 1;
  if (LiveServer* server = g_live_server.load()) server->RequestStopFromSignal();
}

// Installs OnInterrupt for SIGINT and SIGTERM while it lives; restores the old handlers.
class InterruptScope {
 public:
  explicit InterruptScope(LiveServer* server) {
    g_interrupted = 0;
    g_live_server = server;
    struct sigaction action {};
    action.sa_handler = OnInterrupt;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~InterruptScope() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
    g_live_server = nullptr;
  }
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  struct sigaction old_int_ {
  }, old_term_{};
};

std::filesystem::file_time_type ModifiedAt(const std::filesystem::path& file) {
  std::error_code ec;
  const auto t = std::filesystem::last_write_time(file, ec);
  return ec ? std::filesystem::file_time_type::min() : t;
}

// The live page of one refinement (`save` 0 = the one at launch), before its report is
// written: the surgeon sees the pose at once.
void ShowLive(RefineLivePage& live, const CaseSession& session, const RefineOutcome& r, int save) {
  const double refined_s = NowSeconds() - r.start_s;
  if (!live.Show(session, r.analysis, LiveNumbers(r, save)) && save > 0) {
    std::cerr << "occlude: the meshes changed: reload " << live.url() << "\n";
  }
  std::cerr << std::fixed << std::setprecision(2) << "occlude: live page updated "
            << NowSeconds() - r.start_s << " s after the refinement began (refined in " << refined_s
            << " s)\n";
}

// The 3D view's display meshes of the session's jaws, decimated (or read from the cache) on a
// thread of their own while the caller settles a pose.
std::future<DisplayJaws> DecimateForViewerLater(const CaseSession& session) {
  return std::async(std::launch::async, [jaws = session.jaws(), cache = session.cache()] {
    return DecimateJawsForViewer(jaws, cache.get());
  });
}

// --watch: refines from `base` at launch and after every save of the config until
// --max-refinements or Ctrl-C; the live page (`live`, may be null) shows each.
void Watch(const RefineArgs& args, std::unique_ptr<CaseSession> session,
           const Eigen::Isometry3d& base, const std::string& source, RefineLivePage* live) {
  const InterruptScope interrupt(live != nullptr ? &live->server() : nullptr);
  // The report's display meshes, kept while the session lives (the live page keeps its own).
  std::future<DisplayJaws> decimating;
  std::optional<DisplayJaws> display;
  if (live == nullptr) decimating = DecimateForViewerLater(*session);
  const auto display_meshes = [&]() -> const DisplayJaws& {
    if (live != nullptr) return live->Display(*session);
    if (decimating.valid()) display = decimating.get();  // may throw: none kept, made again below
    if (!display) display = DecimateJawsForViewer(session->jaws(), session->cache().get());
    return *display;
  };
  const auto refine = [&](const std::filesystem::path& folder, int save) {
    RefineOutcome r = Refine(*session, base);
    if (live != nullptr) ShowLive(*live, *session, r, save);
    WriteRefinement(*session, r, base, source, folder, display_meshes());
  };
  const std::filesystem::path file = session->config().file;
  refine(OutputFolder(session->config(), args.out), 0);
  if (live != nullptr) std::cerr << "occlude: live page at " << live->url() << "\n";
  std::cerr << "occlude: watching " << file.string()
            << " (Ctrl-C to stop); every save refines from " << source << "\n";
  auto seen = ModifiedAt(file);
  for (int done = 1;
       (args.max_refinements == 0 || done < args.max_refinements) && !g_interrupted;) {
    std::this_thread::sleep_for(std::chrono::duration<double>(args.poll_seconds));
    const auto now = ModifiedAt(file);
    if (g_interrupted || now == seen) continue;
    seen = now;
    ++done;
    try {
      const CaseConfig updated = LoadCaseConfigWithOptions(file, args.landmarks, args.cache);
      if (session->Reusable(updated)) {
        session->UpdateSettings(updated);
      } else {
        std::cerr << "occlude: meshes or accuracy changed: rebuilding the models\n";
        session = std::make_unique<CaseSession>(updated, args.memory_budget_mb);
        display.reset();
        if (live == nullptr) decimating = DecimateForViewerLater(*session);
      }
      refine(OutputFolder(updated, args.out), done - 1);
    } catch (const UserError& e) {
      std::cerr << "occlude: error: " << e.what() << " (still watching)\n";
    }
  }
  if (live != nullptr) live->server().Stop();
  if (g_interrupted) std::cerr << "occlude: stopped (interrupted); the outputs are complete\n";
}

void RunRefine(const RefineArgs& args) {
  const CaseConfig config = LoadCaseConfigWithOptions(args.config, args.landmarks, args.cache);
  PlanRequestFromConfig(config, Eigen::Isometry3d::Identity(),
                        Eigen::Vector3d::Zero());  // settings first
  const std::filesystem::path out = PrepareCaseOutput(config, args.out);
  std::unique_ptr<RefineLivePage> live;  // first: a refused --bind or a busy port fails at once
  if (!args.serve.empty()) live = std::make_unique<RefineLivePage>(args.bind, args.serve.front());
  auto session = std::make_unique<CaseSession>(config, args.memory_budget_mb);
  session->Prefetch();  // the arch analysis and a map field, while the oracle loads and the pose
                        // settles
  Eigen::Isometry3d base = session->ConfigStartPose();
  std::string source = "the config's [start] pose";
  const std::filesystem::path last = out / "pose.json";
  if (!args.from_config && std::filesystem::exists(last)) {
    base = ReadPoseFile(last);
    source = "the last result (" + last.string() + ")";
  }
  if (args.watch) {
    Watch(args, std::move(session), base, source, live.get());
    return;
  }
  // The 3D view's meshes too are decimated while the pose settles.
  std::future<DisplayJaws> display = DecimateForViewerLater(*session);
  RefineOutcome r = Refine(*session, base);
  const DisplayJaws decimated = display.get();
  WriteRefinement(*session, r, base, source, out, decimated);
}

}  // namespace

void AddRefineCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "refine",
      "Apply the config's [adjust] to the last result, re-optimize locally, report what changed");
  auto args = std::make_shared<RefineArgs>();
  cmd->add_option("config", args->config, "Case config file (TOML; see examples/)")->required();
  cmd->add_option("--out", args->out, "Output folder; default: [output] folder of the config");
  AddMemoryBudgetOption(cmd, &args->memory_budget_mb);
  AddLandmarksOption(cmd, &args->landmarks);
  AddCacheOptions(cmd, &args->cache);
  cmd->add_flag("--from-config", args->from_config,
                "Start from the config's [start] pose, not the last result");
  auto* watch = cmd->add_flag("--watch", args->watch,
                              "Keep the trees and refine again on every save of the config file");
  auto* serve = cmd->add_option("--serve", args->serve,
                                "With --watch: serve the live 3D page of the refinements on "
                                "http://127.0.0.1:PORT/ (no PORT: any free port, printed)")
                    ->expected(0, 1)
                    ->check(CLI::Range(0, 65535))
                    ->needs(watch);
  cmd->add_option("--bind", args->bind,
                  "With --serve: listen on this IPv4 address instead of 127.0.0.1 (warns: the "
                  "page shows patient data to anyone who can reach it)")
      ->needs(serve);
  cmd->add_option("--max-refinements", args->max_refinements,
                  "With --watch: stop after this many (0 = never)")
      ->check(CLI::Range(0, 1000000))
      ->group("");  // for scripts and tests
  cmd->callback([args] { RunRefine(*args); });
}

}  // namespace occlude::app
