// The cache of built oracles (the paper's saved IST): each oracle a session builds is saved in
// a folder under its collision::OracleCacheKey (both meshes' content hashes, every option that
// changes what is built, the format version) and loaded from there by the next run instead of
// being built again. Answers of a loaded oracle are bit-identical to a fresh build
// (collision/oracle_file.h).
//
// Folder: the command's --cache DIR, else $XDG_CACHE_HOME/occlude, else ~/.cache/occlude.
// Entries are "oracle-<key as 16 hex digits>.occo", written to a temporary file and renamed
// (a concurrent run never sees half an entry), not flushed to disk (io::Durability::kAtomicOnly:
// an entry a power loss left empty or partly written fails the checks below and is rebuilt). A hit
// touches the entry's mtime; after a save the oldest entries (by mtime) are unlinked until the
// folder's entries fit in `max_mb`; only files of our name and magic are ever removed. A truncated,
// corrupt, foreign or mismatched entry is rebuilt and replaced. A folder that cannot be made, read
// or written is one warning line on the warning stream and the run goes on without it; the cache
// never fails a run.
//
// Beside the oracles, small products of one mesh alone (the arch analysis of a jaw) are kept as
// byte entries "<kind>-<key as 16 hex digits>.occo" (magic, format, key, size and checksum in
// front: ByteEntry*), under the same checks, writes, warnings and size limit.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "occlude/collision/oracle.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// Where and whether a run caches its oracles.
struct OracleCacheSettings {
  bool enabled = true;           ///< false with --no-cache
  std::filesystem::path folder;  ///< --cache DIR; empty = DefaultCacheFolder()
  double max_mb = 2048;          ///< [limits] cache_mb: the entries' total size, MB
};

/// $XDG_CACHE_HOME/occlude when XDG_CACHE_HOME is set and absolute, else $HOME/.cache/occlude;
/// empty when neither is set (the cache is then off).
std::filesystem::path DefaultCacheFolder();

/// The file name of the entry of `key`: "oracle-<16 hex digits>.occo".
std::string OracleCacheEntryName(std::uint64_t key);

/// How the last Get was answered (for tests and the step lines).
enum class OracleCacheOutcome { kOff, kHit, kMiss, kRebuilt };

class OracleCache {
 public:
  /// Warnings (one line each, at most one per kind of trouble) go to `warnings`.
  explicit OracleCache(OracleCacheSettings settings, std::ostream* warnings);

  /// The oracle of these meshes and options: loaded from the folder when an entry of its key
  /// passes every check, else `build()` (then saved, the folder evicted to its limit, and
  /// the saved form read back: a miss answers and reports exactly as a later hit; where the
  /// entry cannot be written, the built oracle, which answers alike).
  /// Get may be called from several threads at once (for different oracles: two runs of one
  /// build would both save it).
  std::unique_ptr<collision::JawOracle> Get(
      std::shared_ptr<const io::TriangleMesh> lower_L,
      std::shared_ptr<const io::TriangleMesh> upper_U, const collision::OracleOptions& options,
      const std::function<std::unique_ptr<collision::JawOracle>()>& build);
  /// Whether the folder has an entry under the key of these meshes and options (not checked:
  /// Get checks it); false when the cache is off.
  bool Holds(const std::shared_ptr<const io::TriangleMesh>& lower_L,
             const std::shared_ptr<const io::TriangleMesh>& upper_U,
             const collision::OracleOptions& options);
  /// io::MeshContentHash of a mesh shared as const (its owners never change it: a session's jaws
  /// and their regions' sub-meshes), computed once per mesh object while it lives: every key of
  /// a run (each stage's region, entry and load) reads it. Thread-safe.
  std::uint64_t MeshHash(const std::shared_ptr<const io::TriangleMesh>& mesh);

  /// The bytes last saved under `kind` (lower-case letters, e.g. "analysis") and `key`, when
  /// the entry passes every check; nullopt when the cache is off or the entry is missing or bad
  /// (a bad one is one line on the warning stream; the caller makes the bytes again and
  /// PutBytes replaces it). Both may be called from several threads at once.
  std::optional<std::string> GetBytes(std::string_view kind, std::uint64_t key);
  /// Saves `bytes` under `kind` and `key` (written then renamed, then the folder evicted to its
  /// limit); a folder that cannot be written is a warning, as for oracles.
  void PutBytes(std::string_view kind, std::uint64_t key, std::string_view bytes);

  /// The folder in use (empty when the cache is off).
  const std::filesystem::path& folder() const { return folder_; }
  /// With Gets on several threads, one of theirs.
  OracleCacheOutcome last_outcome() const { return last_; }

 private:
  std::filesystem::path folder_;
  double max_mb_;
  std::ostream* warnings_;
  std::mutex warn_mutex_;  ///< lines come from the threads of GetBytes and PutBytes too
  bool warned_write_ = false;
  std::atomic<OracleCacheOutcome> last_{OracleCacheOutcome::kOff};
  struct HashedMesh {
    std::weak_ptr<const io::TriangleMesh> owner;
    const io::TriangleMesh* mesh = nullptr;
    std::uint64_t hash = 0;
  };
  std::mutex hash_mutex_;
  std::vector<HashedMesh> hashed_;  ///< MeshHash's, of the meshes still alive
  /// Writes the entry (then evicts to the limit); false, with a warning, when it cannot.
  bool Save(const collision::JawOracle& oracle, const std::filesystem::path& file);
  /// One line on the warning stream; with `once`, only the first time.
  void Warn(const std::string& line, bool* once);
  void WarnNotWritten(const std::string& why);  ///< once per cache
  void Say(const std::string& line);            ///< one line as it is
};

/// What `make()` gives, kept in `cache` as a byte entry of `kind` and key_of(): decoded from
/// the entry when there is one and it decodes (decode throws std::runtime_error otherwise), else
/// made and saved (encode(made) -> bytes). A null cache, or one that is off: made (and the key,
/// a hash of the inputs, never computed).
template <typename Key, typename Make, typename Encode, typename Decode>
auto MadeOrCached(OracleCache* cache, std::string_view kind, Key&& key_of, Make&& make,
                  Encode&& encode, Decode&& decode) -> decltype(make()) {
  if (cache == nullptr || cache->folder().empty()) return make();
  const std::uint64_t key = key_of();
  if (const std::optional<std::string> bytes = cache->GetBytes(kind, key)) {
    try {
      return decode(*bytes);
    } catch (const std::runtime_error&) {
      // An entry of this key that passed its checksum but does not decode: made again.
    }
  }
  auto made = make();
  cache->PutBytes(kind, key, encode(made));
  return made;
}

/// The file name of the byte entry of `kind` and `key`: "<kind>-<16 hex digits>.occo".
std::string ByteEntryName(std::string_view kind, std::uint64_t key);
/// A byte entry's file content: a header (magic, format version, key, size, checksum of the
/// bytes) and the bytes.
std::string ByteEntryFile(std::uint64_t key, std::string_view bytes);
/// The bytes of a byte entry's file content written by ByteEntryFile for `key`; throws
/// std::runtime_error saying what is wrong (not an entry, another format, another key,
/// truncated, checksum) otherwise.
std::string ByteEntryBytes(std::uint64_t key, std::string_view file_content);

/// Unlinks the oldest (by mtime) of the cache entries in `folder` (files named like
/// OracleCacheEntryName or ByteEntryName and starting with the magic of their kind) until their
/// total size is at most `max_bytes`; `keep` is never removed. Errors are ignored (another run
/// may be evicting).
void EvictOracleCache(const std::filesystem::path& folder, std::uintmax_t max_bytes,
                      const std::filesystem::path& keep);

}  // namespace occlude::app
