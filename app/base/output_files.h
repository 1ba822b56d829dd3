// Output files of the commands: folders checked before work starts, and every
// file written atomically (temporary file in the same folder, then renamed), so
// a failed run never leaves a half-written file behind.
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <string>

namespace occlude::app {

/// Creates `dir` (and parents) if needed and checks it is a writable folder.
/// Throws UserError naming the folder and the fix.
void PrepareOutputDir(const std::filesystem::path& dir);

/// Writes `content` to `file` atomically (io::WriteFileAtomically: a reader sees the old file
/// or the new one, never a part). Throws UserError naming the file and the fix.
void WriteFileAtomic(const std::filesystem::path& file, const std::string& content);

/// 4x4 matrix as a JSON-style nested array string (full double precision).
std::string MatrixJson(const Eigen::Matrix4d& m);

}  // namespace occlude::app
