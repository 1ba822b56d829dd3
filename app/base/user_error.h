// occlude::app::UserError: an error the user caused (a bad file, option or
// config key), printed by `occlude` as one line with a non-zero exit. Its own
// header so that code reporting such errors need not include the command-line
// parser (CLI11 costs seconds of compile time per file).
#pragma once

#include <stdexcept>

namespace occlude::app {

/// An error the user caused (bad file, bad option): printed as one line.
class UserError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace occlude::app
