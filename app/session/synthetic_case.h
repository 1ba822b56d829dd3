// The synthetic jaw pair as the commands use it (generation with user-facing
// errors, and writing it out as a case folder).
#pragma once

#include <filesystem>

#include "occlude/io/synthetic_jaws.h"

namespace occlude::app {

/// MakeSyntheticJawPair, with an invalid option reported as a UserError.
io::SyntheticJawPair MakeSyntheticOrExplain(const io::SyntheticJawOptions& options);

/// Writes upper.stl, lower.stl (both in L at the bite), truth.json and landmarks.csv (the
/// designed landmarks of both jaws, in L at the bite) to `dir`.
void WriteSyntheticCase(const io::SyntheticJawPair& pair, const io::SyntheticJawOptions& options,
                        const std::filesystem::path& dir);

}  // namespace occlude::app
