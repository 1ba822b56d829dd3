// The command registry of `occlude` (see commands.h).
#include "cli/commands.h"

namespace occlude::app {

void AddCommands(CLI::App& app) {
  AddSynthCommand(app);
  AddDemoCommand(app);
  AddCollideCommand(app);
  AddProposeCommand(app);
  AddRefineCommand(app);
  AddReportCommand(app);
  AddAnalyzeCommand(app);
  AddBenchCommand(app);
  AddValidateCommand(app);
}

}  // namespace occlude::app
