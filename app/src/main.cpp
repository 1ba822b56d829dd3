// Entry point of the `occlude` command: registers the subcommands and turns
// every error into one line on stderr and a non-zero exit code.
#include <exception>
#include <iostream>

#include "commands.h"

int main(int argc, char** argv) {
  CLI::App app{"occlude: occlusion planning for orthognathic surgery"};
  app.set_version_flag("--version", "occlude 0.1.0");
  app.require_subcommand(1);
  occlude::app::AddSynthCommand(app);
  occlude::app::AddDemoCommand(app);
  occlude::app::AddCollideCommand(app);
  occlude::app::AddProposeCommand(app);
  occlude::app::AddRefineCommand(app);
  occlude::app::AddReportCommand(app);
  occlude::app::AddBenchCommand(app);
  occlude::app::AddValidateCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const occlude::app::UserError& e) {
    std::cerr << "occlude: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "occlude: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
