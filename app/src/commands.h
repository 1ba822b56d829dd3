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

/// Validator for a length option: a finite number of millimetres above zero.
inline CLI::Validator PositiveMm() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double v = std::stod(text, &used);
          if (used == text.size() && v > 0.0 && v < 1e6) return "";
        } catch (const std::exception&) {
        }
        return "must be a positive length in mm, got '" + text + "'";
      },
      "MM>0");
}

/// Validator for a contact band: a finite number of millimetres in [0, 5].
inline CLI::Validator BandMm() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double v = std::stod(text, &used);
          if (used == text.size() && v >= 0.0 && v <= 5.0) return "";
        } catch (const std::exception&) {
        }
        return "must be a band in mm between 0 and 5, got '" + text + "'";
      },
      "0..5 MM");
}

void AddSynthCommand(CLI::App& app);
void AddDemoCommand(CLI::App& app);
void AddCollideCommand(CLI::App& app);

}  // namespace occlude::app
