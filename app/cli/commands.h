// The subcommands of `occlude`, one file each (cli/cmd_<name>.cpp). Each Add*Command registers
// its options on the CLI11 app and a callback that does the work; errors are thrown as
// occlude::app::UserError (one line, non-zero exit). A new command is one Add*Command here, its
// file, and one line in AddCommands (commands.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace occlude::app {

/// Registers every subcommand on `app`, in the order `occlude --help` lists them.
void AddCommands(CLI::App& app);

void AddSynthCommand(CLI::App& app);
void AddDemoCommand(CLI::App& app);
void AddCollideCommand(CLI::App& app);
void AddProposeCommand(CLI::App& app);
void AddRefineCommand(CLI::App& app);
void AddReportCommand(CLI::App& app);
void AddAnalyzeCommand(CLI::App& app);
void AddBenchCommand(CLI::App& app);
void AddValidateCommand(CLI::App& app);

}  // namespace occlude::app
