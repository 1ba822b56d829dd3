// Entry point of the `occlude` command: registers the subcommands and turns
// every error into one line on stderr and a non-zero exit code: 1 for errors
// the user can fix (bad file, key or option), 2 for anything else (a bug, or
// the machine running out of memory), each still one line.
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "base/user_error.h"
#include "cli/commands.h"

namespace {

// Prints "occlude: error: <what>" as one line, after what the command already
// printed on stdout (so the error is the last line of a merged output).
int Report(const std::string& what, int code) {
  std::cout.flush();
  std::string line = what;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::cerr << "occlude: error: " << line << "\n";
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"occlude: occlusion planning for orthognathic surgery"};
  app.set_version_flag("--version", "occlude 0.1.0");
  app.require_subcommand(1);
  occlude::app::AddCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::cout.flush();
    return app.exit(e);
  } catch (const occlude::app::UserError& e) {
    return Report(e.what(), 1);
  } catch (const std::bad_alloc&) {
    return Report(
        "out of memory; use a coarser voxel size or lower --memory-budget-mb so that the memory "
        "guard stops such runs before they start",
        2);
  } catch (const std::exception& e) {
    return Report(e.what(), 2);
  }
  return 0;
}
