// The oracle cache (oracle_cache.h): lookup, save, least-recently-used eviction by mtime.
#include "session/oracle_cache.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "occlude/collision/oracle_file.h"
#include "occlude/io/atomic_file.h"
#include "occlude/io/mesh_io.h"

namespace occlude::app {
namespace fs = std::filesystem;

namespace {

constexpr char kCacheEntryPrefix[] = "oracle-";
constexpr char kCacheEntrySuffix[] = ".occo";
constexpr char kSavedOracleMagic[] = "OCCLORCL";

// True for a file named like an entry whose first bytes are the saved-oracle magic.
bool IsCacheEntry(const fs::path& file) {
  const std::string name = file.filename().string();
  const std::string prefix = kCacheEntryPrefix, suffix = kCacheEntrySuffix;
  if (name.size() != prefix.size() + 16 + suffix.size() || name.rfind(prefix, 0) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return false;
  }
  std::ifstream in(file, std::ios::binary);
  char magic[8] = {};
  return in.read(magic, sizeof magic) && std::equal(magic, magic + 8, kSavedOracleMagic);
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
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(key));
  return kCacheEntryPrefix + std::string(hex) + kCacheEntrySuffix;
}

OracleCache::OracleCache(OracleCacheSettings settings, std::ostream* warnings)
    : max_mb_(settings.max_mb), warnings_(warnings) {
  if (settings.enabled) folder_ = settings.folder.empty() ? DefaultCacheFolder() : settings.folder;
}

void OracleCache::Warn(const std::string& line, bool* once) {
  if (*once || warnings_ == nullptr) return;
  *once = true;
  *warnings_ << "occlude: warning: " << line << "\n";
}

std::unique_ptr<collision::JawOracle> OracleCache::Get(
    std::shared_ptr<const io::TriangleMesh> lower_L,
    std::shared_ptr<const io::TriangleMesh> upper_U, const collision::OracleOptions& options,
    const std::function<std::unique_ptr<collision::JawOracle>()>& build) {
  if (folder_.empty()) {
    last_ = OracleCacheOutcome::kOff;
    return build();
  }
  const fs::path file =
      folder_ / OracleCacheEntryName(collision::OracleCacheKey(*lower_L, *upper_U, options));
  std::error_code ec;
  last_ = OracleCacheOutcome::kMiss;
  if (fs::exists(file, ec)) {
    try {
      auto oracle = std::make_unique<collision::JawOracle>(
          collision::LoadOracleFile(file, lower_L, upper_U, options));
      fs::last_write_time(file, fs::file_time_type::clock::now(), ec);  // the LRU touch
      last_ = OracleCacheOutcome::kHit;
      return oracle;
    } catch (const collision::OracleFileError& e) {
      if (warnings_ != nullptr) {
        *warnings_ << "occlude: cache entry not used (" << e.what() << "); rebuilding it\n";
      }
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
        collision::LoadOracleFile(file, lower_L, upper_U, options));
  } catch (const collision::OracleFileError& e) {
    // Only if another run removed or replaced the entry meanwhile: build it again, uncached.
    if (warnings_ != nullptr) {
      *warnings_ << "occlude: cache entry not read back (" << e.what() << "); building it again\n";
    }
    return build();
  }
}

bool OracleCache::Save(const collision::JawOracle& oracle, const fs::path& file) {
  std::error_code ec;
  fs::create_directories(folder_, ec);
  try {
    if (ec) throw io::MeshError(folder_.string() + ": " + ec.message());
    collision::SaveOracleFile(oracle, file);
  } catch (const std::exception& e) {
    Warn("oracle cache not written (" + std::string(e.what()) +
             "); going on without it (--cache DIR for another folder, --no-cache to skip it)",
         &warned_write_);
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
