// `occlude propose CASE.toml [--out DIR] [--landmarks FILE] [--global]`: the automated occlusion
// proposal
// (report/proposal_report.h): searches from the config's start pose with the config's solver
// and writes the K proposals and the full report of the best.
#include <memory>
#include <string>

#include "cli/cache_options.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "config/case_config.h"
#include "report/proposal_report.h"

namespace occlude::app {
namespace {

struct ProposeArgs {
  std::string config;
  std::string out;
  std::string landmarks;
  double memory_budget_mb = 0;
  bool global = false;
  CacheArgs cache;
};

void RunPropose(const ProposeArgs& args) {
  CaseConfig config = LoadCaseConfigWithOptions(args.config, args.landmarks, args.cache);
  if (args.global) config.solver.scope = "global";
  ProposeAndReport(config, args.out, args.memory_budget_mb);
}

}  // namespace

void AddProposeCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand("propose",
                                 "Search the occlusion: the K best distinct poses of the upper "
                                 "jaw, and the report of the best");
  auto args = std::make_shared<ProposeArgs>();
  cmd->add_option("config", args->config, "Case config file (TOML; see examples/)")->required();
  cmd->add_option("--out", args->out, "Output folder; default: [output] folder of the config");
  cmd->add_flag("--global", args->global,
                "Global scope (overrides solver.scope): no start pose, every intercuspation of "
                "the two arches, ranked by [clinical]");
  AddMemoryBudgetOption(cmd, &args->memory_budget_mb);
  AddLandmarksOption(cmd, &args->landmarks);
  AddCacheOptions(cmd, &args->cache);
  cmd->callback([args] { RunPropose(*args); });
}

}  // namespace occlude::app
