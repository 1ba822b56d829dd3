// Whole-file writes that never leave a half-written file (for outputs and caches shared by
// processes running at the same time).
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace occlude::io {

/// Whether an atomic write is flushed to disk before its rename.
enum class Durability {
  /// Flushed (fsync) first: after a crash or a power loss the file is the old one or the new
  /// one, whole. For outputs.
  kDurable,
  /// Not flushed: a concurrent reader still sees the old file or the new one, never a part, but
  /// after a power loss the new file may be empty or partly written. For caches, whose readers
  /// check every entry (size, checksum) and make a bad one again; saves the flush (a-bite's
  /// 0.2 mm oracle, 132 MB: about 65 ms).
  kAtomicOnly,
};

/// Replaces `file` by `bytes` atomically (a temporary file in the same folder, flushed as
/// `durability` says, then renamed over it: a concurrent reader sees the old file or the new
/// one, never a part). Throws MeshError (mesh_io.h) naming `file` (folder missing or not
/// writable, disk full); never leaves the temporary file behind when it throws.
void WriteFileAtomically(const std::filesystem::path& file, const std::string& bytes,
                         Durability durability = Durability::kDurable);

/// The same, written in pieces (a file too large to hold in memory at once): Append() the
/// bytes in order, Overwrite() some already appended (a header known at the end), Commit() to
/// put the file in place. Destroyed uncommitted (or after a throw), it leaves nothing behind.
/// Every member throws MeshError naming `file` as WriteFileAtomically does.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(const std::filesystem::path& file,
                            Durability durability = Durability::kDurable);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void Append(std::string_view bytes);
  /// Replaces bytes [offset, offset + bytes.size()) of those appended so far.
  void Overwrite(std::size_t offset, std::string_view bytes);
  void Commit();

 private:
  struct Temp;
  std::unique_ptr<Temp> temp_;
  std::size_t size_ = 0;
  Durability durability_;
};

}  // namespace occlude::io
