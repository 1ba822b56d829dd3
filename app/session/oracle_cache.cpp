// The oracle cache (oracle_cache.h): lookup, save, least-recently-used eviction by mtime.
#include "session/oracle_cache.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "occlude/collision/oracle_file.h"
#include "occlude/io/atomic_file.h"
#include "occlude/io/content_hash.h"
#include "occlude/io/mesh_io.h"
#include "session/byte_fields.h"

namespace occlude::app {
namespace fs = std::filesystem;

namespace {

constexpr char kOracleKind[] = "oracle";
constexpr char kEntrySuffix[] = ".occo";
constexpr char kSavedOracleMagic[] = "OCCLORCL";
constexpr char kByteEntryMagic[] = "OCCLBYTE";
constexpr std::uint32_t kByteEntryFormat = 1;
/// magic, format, a zero word, key, size, checksum
constexpr std::size_t kByteEntryHeader = 8 + 4 + 4 + 8 + 8 + 8;

bool IsKind(std::string_view kind) {
  return !kind.empty() &&
         std::all_of(kind.begin(), kind.end(), [](char c) { return c >= 'a' && c <= 'z'; });
}

// The kind of a file named like an entry, "<kind>-<16 hex digits>.occo"; empty for any other.
std::string EntryKind(const std::string& name) {
  const std::string suffix = kEntrySuffix;
  const std::size_t tail = 1 + 16 + suffix.size();
  if (name.size() <= tail || name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return {};
  const std::string kind = name.substr(0, name.size() - tail);
  const std::string hex = name.substr(kind.size() + 1, 16);
  const bool is_hex = std::all_of(hex.begin(), hex.end(), [](char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
  });
  return name[kind.size()] == '-' && is_hex && IsKind(kind) ? kind : std::string();
}

// True for a file named like an entry whose first bytes are the magic of its kind.
bool IsCacheEntry(const fs::path& file) {
  const std::string kind = EntryKind(file.filename().string());
  if (kind.empty()) return false;
  std::ifstream in(file, std::ios::binary);
  char magic[8] = {};
  const char* expected = kind == kOracleKind ? kSavedOracleMagic : kByteEntryMagic;
  return in.read(magic, sizeof magic) && std::equal(magic, magic + 8, expected);
}

// The whole file, or nullopt when it cannot be opened or read.
std::optional<std::string> ReadWholeFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::string content;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) return std::nullopt;
  content.resize(static_cast<std::size_t>(size));
  in.seekg(0);
  if (!in.read(content.data(), size)) return std::nullopt;
  return content;
}

}  // namespace

fs::path DefaultCacheFolder() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg != nullptr && fs::path(xdg).is_absolute()) return fs::path(xdg) / "occlude";
  const char* home = std::getenv("HOME");
  if (home != nullptr && *home != '\0') return fs::path(home) / ".cache" / "occlude";
  return {};
}

std::string OracleCacheEntryName(std::uint64_t key) {
  return kOracleKind + ("-" + io::HashHex(key)) + kEntrySuffix;
}

std::string ByteEntryName(std::string_view kind, std::uint64_t key) {
  if (!IsKind(kind) || kind == kOracleKind) {
    throw std::invalid_argument("ByteEntryName: kind '" + std::string(kind) +
                                "' must be lower-case letters and not \"oracle\"");
  }
  return std::string(kind) + "-" + io::HashHex(key) + kEntrySuffix;
}

std::string ByteEntryFile(std::uint64_t key, std::string_view bytes) {
  std::string file(kByteEntryMagic, 8);
  PutValue(&file, kByteEntryFormat);
  PutValue(&file, std::uint32_t{0});
  PutValue(&file, key);
  PutValue(&file, static_cast<std::uint64_t>(bytes.size()));
  PutValue(&file, io::Hash64(bytes.data(), bytes.size(), key));
  file.append(bytes);
  return file;
}

std::string ByteEntryBytes(std::uint64_t key, std::string_view file) {
  if (file.size() < kByteEntryHeader || file.compare(0, 8, kByteEntryMagic) != 0)
    throw std::runtime_error("not a byte entry (no header)");
  if (ValueAt<std::uint32_t>(file, 8) != kByteEntryFormat)
    throw std::runtime_error("format " + std::to_string(ValueAt<std::uint32_t>(file, 8)) +
                             ", expected " + std::to_string(kByteEntryFormat));
  if (ValueAt<std::uint64_t>(file, 16) != key) throw std::runtime_error("the entry of another key");
  const auto size = ValueAt<std::uint64_t>(file, 24);
  if (size != file.size() - kByteEntryHeader) {
    throw std::runtime_error("truncated or extended: " + std::to_string(file.size()) +
                             " bytes, the header says " + std::to_string(size + kByteEntryHeader));
  }
  const std::string_view bytes = file.substr(kByteEntryHeader);
  if (io::Hash64(bytes.data(), bytes.size(), key) != ValueAt<std::uint64_t>(file, 32))
    throw std::runtime_error("checksum mismatch");
  return std::string(bytes);
}

OracleCache::OracleCache(OracleCacheSettings settings, std::ostream* warnings)
    : max_mb_(settings.max_mb), warnings_(warnings) {
  if (settings.enabled) folder_ = settings.folder.empty() ? DefaultCacheFolder() : settings.folder;
}

void OracleCache::Warn(const std::string& line, bool* once) {
  const std::lock_guard<std::mutex> lock(warn_mutex_);
  if (warnings_ == nullptr || (once != nullptr && *once)) return;
  if (once != nullptr) *once = true;
  *warnings_ << "occlude: warning: " << line << "\n";
}

void OracleCache::Say(const std::string& line) {
  const std::lock_guard<std::mutex> lock(warn_mutex_);
  if (warnings_ != nullptr) *warnings_ << line << "\n";
}

std::unique_ptr<collision::JawOracle> OracleCache::Get(
    std::shared_ptr<const io::TriangleMesh> lower_L,
    std::shared_ptr<const io::TriangleMesh> upper_U, const collision::OracleOptions& options,
    const std::function<std::unique_ptr<collision::JawOracle>()>& build) {
  if (folder_.empty()) {
    last_ = OracleCacheOutcome::kOff;
    return build();
  }
  const std::uint64_t key =
      collision::OracleCacheKey(MeshHash(lower_L), MeshHash(upper_U), options);
  const fs::path file = folder_ / OracleCacheEntryName(key);
  std::error_code ec;
  last_ = OracleCacheOutcome::kMiss;
  if (fs::exists(file, ec)) {
    try {
      auto oracle = std::make_unique<collision::JawOracle>(
          collision::LoadOracleFile(file, lower_L, upper_U, options, key));
      fs::last_write_time(file, fs::file_time_type::clock::now(), ec);  // the LRU touch
      last_ = OracleCacheOutcome::kHit;
      return oracle;
    } catch (const collision::OracleFileError& e) {
      Say(std::string("occlude: cache entry not used (") + e.what() + "); rebuilding it");
      last_ = OracleCacheOutcome::kRebuilt;
    }
  }
  std::unique_ptr<collision::JawOracle> built = build();
  if (!Save(*built, file)) return built;
  // The run goes on with the saved form, so that a miss and a later hit are the same object
  // (down to MemoryBytes(), which counts a built oracle's spare capacity). The built one goes
  // first: the file is read back a section at a time, so the two are never held at once.
  built.reset();
  try {
    return std::make_unique<collision::JawOracle>(
        collision::LoadOracleFile(file, lower_L, upper_U, options, key));
  } catch (const collision::OracleFileError& e) {
    // Only if another run removed or replaced the entry meanwhile: build it again, uncached.
    Say(std::string("occlude: cache entry not read back (") + e.what() + "); building it again");
    return build();
  }
}

bool OracleCache::Holds(const std::shared_ptr<const io::TriangleMesh>& lower_L,
                        const std::shared_ptr<const io::TriangleMesh>& upper_U,
                        const collision::OracleOptions& options) {
  if (folder_.empty()) return false;
  std::error_code ec;
  return fs::exists(folder_ / OracleCacheEntryName(collision::OracleCacheKey(
                                  MeshHash(lower_L), MeshHash(upper_U), options)),
                    ec);
}

std::uint64_t OracleCache::MeshHash(const std::shared_ptr<const io::TriangleMesh>& mesh) {
  // The same object: the same address and owner, still alive (a dead one's address may hold
  // another mesh by now).
  const auto same = [&](const HashedMesh& h) {
    return h.mesh == mesh.get() && !h.owner.owner_before(mesh) && !mesh.owner_before(h.owner) &&
           !h.owner.expired();
  };
  {
    const std::lock_guard<std::mutex> lock(hash_mutex_);
    for (const HashedMesh& h : hashed_) {
      if (same(h)) return h.hash;
    }
  }
  const std::uint64_t hash = io::MeshContentHash(*mesh);  // outside the lock: meshes hash at once
  const std::lock_guard<std::mutex> lock(hash_mutex_);
  hashed_.erase(std::remove_if(hashed_.begin(), hashed_.end(),
                               [](const HashedMesh& h) { return h.owner.expired(); }),
                hashed_.end());
  hashed_.push_back({mesh, mesh.get(), hash});
  return hash;
}

std::optional<std::string> OracleCache::GetBytes(std::string_view kind, std::uint64_t key) {
  if (folder_.empty()) return std::nullopt;
  const fs::path file = folder_ / ByteEntryName(kind, key);
  const std::optional<std::string> content = ReadWholeFile(file);
  if (!content) return std::nullopt;
  try {
    std::string bytes = ByteEntryBytes(key, *content);
    std::error_code ec;
    fs::last_write_time(file, fs::file_time_type::clock::now(), ec);  // the LRU touch
    return bytes;
  } catch (const std::runtime_error& e) {
    Warn("cache entry not used (" + file.string() + ": " + e.what() + "); making it again",
         nullptr);
    return std::nullopt;
  }
}

void OracleCache::PutBytes(std::string_view kind, std::uint64_t key, std::string_view bytes) {
  if (folder_.empty()) return;
  const fs::path file = folder_ / ByteEntryName(kind, key);
  std::error_code ec;
  fs::create_directories(folder_, ec);
  try {
    if (ec) throw io::MeshError(folder_.string() + ": " + ec.message());
    io::WriteFileAtomically(file, ByteEntryFile(key, bytes), io::Durability::kAtomicOnly);
  } catch (const std::exception& e) {
    WarnNotWritten(e.what());
    return;
  }
  EvictOracleCache(folder_, static_cast<std::uintmax_t>(max_mb_ * 1024.0 * 1024.0), file);
}

void OracleCache::WarnNotWritten(const std::string& why) {
  Warn("oracle cache not written (" + why +
           "); going on without it (--cache DIR for another folder, --no-cache to skip it)",
       &warned_write_);
}

bool OracleCache::Save(const collision::JawOracle& oracle, const fs::path& file) {
  std::error_code ec;
  fs::create_directories(folder_, ec);
  try {
    if (ec) throw io::MeshError(folder_.string() + ": " + ec.message());
    collision::SaveOracleFile(oracle, file, io::Durability::kAtomicOnly);
  } catch (const std::exception& e) {
    WarnNotWritten(e.what());
    return false;
  }
  EvictOracleCache(folder_, static_cast<std::uintmax_t>(max_mb_ * 1024.0 * 1024.0), file);
  return true;
}

void EvictOracleCache(const fs::path& folder, std::uintmax_t max_bytes, const fs::path& keep) {
  struct Entry {
    fs::file_time_type mtime;
    std::uintmax_t bytes;
    fs::path file;
  };
  std::vector<Entry> entries;
  std::uintmax_t total = 0;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path file = it->path();
    std::error_code size_ec, time_ec;
    const std::uintmax_t bytes = fs::file_size(file, size_ec);
    const fs::file_time_type mtime = fs::last_write_time(file, time_ec);
    if (size_ec || time_ec || !IsCacheEntry(file)) continue;
    entries.push_back({mtime, bytes, file});
    total += bytes;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.mtime != b.mtime ? a.mtime < b.mtime : a.file < b.file;
  });
  for (const Entry& entry : entries) {
    if (total <= max_bytes) break;
    if (entry.file == keep) continue;
    std::error_code remove_ec;
    if (fs::remove(entry.file, remove_ec)) total -= entry.bytes;
  }
}

}  // namespace occlude::app
