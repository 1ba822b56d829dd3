// Whole-file writes that never leave a half-written file (for outputs and caches shared by
// processes running at the same time).
#pragma once

#include <filesystem>
#include <string>

namespace occlude::io {

/// Replaces `file` by `bytes` atomically (a temporary file in the same folder, flushed, then
/// renamed over it: a concurrent reader sees the old file or the new one, never a part).
/// Throws MeshError (mesh_io.h) naming `file` (folder missing or not writable, disk full);
/// never leaves the temporary file behind when it throws.
void WriteFileAtomically(const std::filesystem::path& file, const std::string& bytes);

}  // namespace occlude::io
