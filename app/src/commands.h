// The subcommands of `occlude`. Each Add*Command registers its options on the
// CLI11 app and a callback that does the work; errors are thrown as
// occlude::app::UserError (one line, non-zero exit).
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

namespace occlude::app {

/// An error the user caused (bad file, bad option): printed as one line.
class UserError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

void AddSynthCommand(CLI::App& app);
void AddDemoCommand(CLI::App& app);
void AddCollideCommand(CLI::App& app);

}  // namespace occlude::app
