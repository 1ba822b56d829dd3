// The oracle cache (session/oracle_cache.h) on a small synthetic bite at coarse voxels: a hit
// answers bit-identically to a fresh build; a changed mesh byte or setting misses; truncated,
// corrupt and foreign entries are rebuilt and replaced; concurrent writers leave one valid
// entry; eviction removes the least recently used entries of our format only; a read-only
// folder is one warning line. Byte entries (the arch analyses) likewise: read back as written,
// any damage or another key refused with one warning line, counted by eviction. Every test uses
// its own temporary folder.
#include "session/oracle_cache.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "occlude/collision/oracle_file.h"
#include "occlude/io/content_hash.h"
#include "session/jaw_pair.h"
#include "test_common.h"

namespace occlude::app {
namespace {

namespace fs = std::filesystem;
using test::TempDir;
using MeshPtr = std::shared_ptr<const io::TriangleMesh>;

class OracleCacheTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    jaws_ = new JawPair(AtReference(SyntheticJawPair(5000, 5)));
    options_.voxel_size_mm = 0.8;
    fresh_ = new collision::JawOracle(jaws_->lower_L, jaws_->upper_U, options_);
  }
  static void TearDownTestSuite() {
    delete fresh_;
    delete jaws_;
  }

  // A "build" of the suite's oracle (a copy of the one built once), or a real one for other
  // meshes or options.
  static std::unique_ptr<collision::JawOracle> Build(MeshPtr lower,
                                                     const collision::OracleOptions& options) {
    if (lower == jaws_->lower_L && options.sample_spacing_mm == options_.sample_spacing_mm) {
      return std::make_unique<collision::JawOracle>(*fresh_);
    }
    return std::make_unique<collision::JawOracle>(lower, jaws_->upper_U, options);
  }

  // Gets the oracle through a cache in `folder`, counting builds.
  std::unique_ptr<collision::JawOracle> Get(const fs::path& folder, OracleCacheOutcome* outcome,
                                            const collision::OracleOptions& options = options_,
                                            MeshPtr lower = nullptr) {
    OracleCacheSettings settings;
    settings.folder = folder;
    OracleCache cache(settings, &warnings_);
    const MeshPtr l = lower ? lower : jaws_->lower_L;
    auto oracle = cache.Get(l, jaws_->upper_U, options, [&] {
      ++builds_;
      return Build(l, options);
    });
    *outcome = cache.last_outcome();
    return oracle;
  }

  // The hash of the answers at a few poses about the reference, at every level.
  static std::uint64_t Digest(const collision::JawOracle& oracle) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> shift(-0.4, 0.4);
    io::Hasher64 hash;
    for (int i = 0; i < 6; ++i) {
      const Eigen::Isometry3d X(
          Eigen::Translation3d(Eigen::Vector3d(shift(rng), shift(rng), shift(rng))));
      for (const auto level :
           {collision::AccuracyLevel::kVoxel, collision::AccuracyLevel::kSubVoxel,
            collision::AccuracyLevel::kExact}) {
        collision::OracleRequest request;
        request.level = level;
        collision::OracleResult result;
        oracle.Query(X, request, &result);
        collision::HashOracleResult(result, &hash);
      }
    }
    return hash.Finish();
  }

  fs::path EntryOf(const fs::path& folder) const {
    return folder / OracleCacheEntryName(
                        collision::OracleCacheKey(*jaws_->lower_L, *jaws_->upper_U, options_));
  }

  static JawPair* jaws_;
  static collision::OracleOptions options_;
  static collision::JawOracle* fresh_;
  std::ostringstream warnings_;
  int builds_ = 0;
};
JawPair* OracleCacheTest::jaws_ = nullptr;
collision::OracleOptions OracleCacheTest::options_;
collision::JawOracle* OracleCacheTest::fresh_ = nullptr;

TEST_F(OracleCacheTest, SecondGetIsAHitThatAnswersBitIdenticallyToAFreshBuild) {
  TempDir dir;
  OracleCacheOutcome outcome;
  const auto built = Get(dir.path(), &outcome);
  EXPECT_EQ(outcome, OracleCacheOutcome::kMiss);
  ASSERT_TRUE(fs::exists(EntryOf(dir.path())));
  const auto loaded = Get(dir.path(), &outcome);
  EXPECT_EQ(outcome, OracleCacheOutcome::kHit);
  EXPECT_EQ(builds_, 1);
  EXPECT_EQ(Digest(*loaded), Digest(*fresh_));
  EXPECT_EQ(Digest(*built), Digest(*fresh_));
  // A miss goes on with the saved form: the same MemoryBytes() (metrics.json) as a hit.
  EXPECT_EQ(loaded->MemoryBytes(), built->MemoryBytes());
  EXPECT_EQ(warnings_.str(), "");
}

// Holds tells whether an entry of the key is there (the session reads those at once): not
// before the first Get, then yes; not for other settings, nor when the cache is off.
TEST_F(OracleCacheTest, HoldsSaysWhetherTheEntryIsThere) {
  TempDir dir;
  OracleCacheSettings settings;
  settings.folder = dir.path();
  OracleCache cache(settings, &warnings_);
  EXPECT_FALSE(cache.Holds(jaws_->lower_L, jaws_->upper_U, options_));
  OracleCacheOutcome outcome;
  Get(dir.path(), &outcome);
  EXPECT_TRUE(cache.Holds(jaws_->lower_L, jaws_->upper_U, options_));
  collision::OracleOptions other = options_;
  other.sample_spacing_mm *= 1.5;
  EXPECT_FALSE(cache.Holds(jaws_->lower_L, jaws_->upper_U, other));
  OracleCacheSettings off;
  off.enabled = false;
  off.folder = dir.path();
  EXPECT_FALSE(OracleCache(off, &warnings_).Holds(jaws_->lower_L, jaws_->upper_U, options_));
}

// MeshHash is io::MeshContentHash, remembered per living mesh object: a copy with one vertex
// moved, and a new mesh made after the first is gone (perhaps at its address), hash anew; the
// keys from hashes equal those from meshes.
TEST_F(OracleCacheTest, MeshHashIsTheContentHashOfEachLivingMesh) {
  OracleCacheSettings off;
  off.enabled = false;
  OracleCache cache(off, &warnings_);
  const std::uint64_t lower = cache.MeshHash(jaws_->lower_L);
  EXPECT_EQ(lower, io::MeshContentHash(*jaws_->lower_L));
  EXPECT_EQ(cache.MeshHash(jaws_->lower_L), lower);
  EXPECT_EQ(cache.MeshHash(jaws_->upper_U), io::MeshContentHash(*jaws_->upper_U));
  auto moved = std::make_shared<io::TriangleMesh>(*jaws_->lower_L);
  moved->vertices[3].y() += 1e-6;
  std::shared_ptr<const io::TriangleMesh> copy = moved;
  EXPECT_EQ(cache.MeshHash(copy), io::MeshContentHash(*moved));
  EXPECT_NE(cache.MeshHash(copy), lower);
  for (int i = 0; i < 4; ++i) {  // new meshes, one after the other, where the last one died
    copy.reset();
    moved.reset();
    auto next = std::make_shared<io::TriangleMesh>(*jaws_->upper_U);
    next->vertices[static_cast<std::size_t>(i)].x() += 0.5;
    copy = next;
    EXPECT_EQ(cache.MeshHash(copy), io::MeshContentHash(*next)) << i;
  }
  EXPECT_EQ(collision::OracleCacheKey(lower, cache.MeshHash(jaws_->upper_U), options_),
            collision::OracleCacheKey(*jaws_->lower_L, *jaws_->upper_U, options_));
}

TEST_F(OracleCacheTest, AChangedMeshByteOrSettingMisses) {
  TempDir dir;
  OracleCacheOutcome outcome;
  Get(dir.path(), &outcome);
  collision::OracleOptions other = options_;
  other.sample_spacing_mm *= 1.5;
  Get(dir.path(), &outcome, other);
  EXPECT_EQ(outcome, OracleCacheOutcome::kMiss);
  auto moved = std::make_shared<io::TriangleMesh>(*jaws_->lower_L);
  moved->vertices[0].x() += 1e-3;
  Get(dir.path(), &outcome, options_, moved);
  EXPECT_EQ(outcome, OracleCacheOutcome::kMiss);
  EXPECT_EQ(builds_, 3);
  Get(dir.path(), &outcome);
  EXPECT_EQ(outcome, OracleCacheOutcome::kHit);
}

TEST_F(OracleCacheTest, TruncatedCorruptAndForeignEntriesAreRebuiltAndReplaced) {
  TempDir dir;
  OracleCacheOutcome outcome;
  const auto first = Get(dir.path(), &outcome);
  const std::uint64_t digest = Digest(*first);
  const fs::path entry = EntryOf(dir.path());
  const std::uintmax_t size = fs::file_size(entry);
  for (const std::string damage : {"truncated", "corrupt", "foreign"}) {
    if (damage == "truncated") fs::resize_file(entry, size / 2);
    if (damage == "corrupt") {
      std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
      f.seekp(static_cast<std::streamoff>(size - 7));
      f.put('\x5a');
    }
    if (damage == "foreign") std::ofstream(entry, std::ios::binary) << "solid x\nendsolid x\n";
    const auto rebuilt = Get(dir.path(), &outcome);
    EXPECT_EQ(outcome, OracleCacheOutcome::kRebuilt) << damage;
    EXPECT_EQ(Digest(*rebuilt), digest) << damage;
    EXPECT_EQ(fs::file_size(entry), size) << damage;  // replaced by a whole entry
    Get(dir.path(), &outcome);
    EXPECT_EQ(outcome, OracleCacheOutcome::kHit) << damage;
  }
  EXPECT_NE(warnings_.str().find("rebuilding"), std::string::npos) << warnings_.str();
}

TEST_F(OracleCacheTest, ConcurrentWritersLeaveOneValidEntryAndNoTemporaryFiles) {
  TempDir dir;
  std::atomic<int> builds{0};
  auto run = [&] {
    OracleCacheSettings settings;
    settings.folder = dir.path();
    OracleCache cache(settings, nullptr);
    for (int i = 0; i < 3; ++i) {
      cache.Get(jaws_->lower_L, jaws_->upper_U, options_, [&] {
        ++builds;
        return Build(jaws_->lower_L, options_);
      });
    }
  };
  std::thread a(run), b(run);
  a.join();
  b.join();
  EXPECT_GE(builds.load(), 1);
  EXPECT_LE(builds.load(), 2);  // each writer builds at most once, then hits
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir.path())) {
    ++files;
    EXPECT_EQ(e.path(), EntryOf(dir.path()));
  }
  EXPECT_EQ(files, 1);
  OracleCacheOutcome outcome;
  Get(dir.path(), &outcome);
  EXPECT_EQ(outcome, OracleCacheOutcome::kHit);
}

TEST_F(OracleCacheTest, EvictionRemovesTheLeastRecentlyUsedEntriesOfOurFormatOnly) {
  TempDir dir;
  OracleCacheOutcome outcome;
  Get(dir.path(), &outcome);
  const fs::path entry = EntryOf(dir.path());
  const std::uintmax_t size = fs::file_size(entry);
  // Three copies of the entry under other keys, aged oldest to newest, and a foreign file
  // named like an entry.
  const auto now = fs::file_time_type::clock::now();
  std::vector<fs::path> copies;
  for (int i = 0; i < 3; ++i) {
    copies.push_back(dir / OracleCacheEntryName(0x100 + i));
    fs::copy_file(entry, copies.back());
    fs::last_write_time(copies.back(), now - std::chrono::hours(3 - i));
  }
  const fs::path foreign = dir / OracleCacheEntryName(0x999);
  std::ofstream(foreign) << "not an oracle";
  fs::last_write_time(foreign, now - std::chrono::hours(10));
  EvictOracleCache(dir.path(), 2 * size, entry);
  EXPECT_TRUE(fs::exists(entry));
  EXPECT_FALSE(fs::exists(copies[0]));
  EXPECT_FALSE(fs::exists(copies[1]));
  EXPECT_TRUE(fs::exists(copies[2]));
  EXPECT_TRUE(fs::exists(foreign));
  // A hit touches: the oldest entry, once hit, outlives a newer one.
  fs::last_write_time(entry, now - std::chrono::hours(5));
  Get(dir.path(), &outcome);
  EXPECT_EQ(outcome, OracleCacheOutcome::kHit);
  EvictOracleCache(dir.path(), size, "");
  EXPECT_TRUE(fs::exists(entry));
  EXPECT_FALSE(fs::exists(copies[2]));
}

// Read-only for a user; for root (who writes anywhere) a folder under a regular file, which
// cannot be made either.
TEST_F(OracleCacheTest, AnUnwritableFolderIsOneWarningLineNotAFailure) {
  TempDir dir;
  fs::path folder = dir / "ro";
  fs::create_directory(folder);
  fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec);
  if (geteuid() == 0) {
    std::ofstream(dir / "file") << "x";
    folder = dir / "file" / "cache";
  }
  OracleCacheOutcome outcome;
  EXPECT_NE(Get(folder, &outcome), nullptr);
  EXPECT_NE(Get(folder, &outcome), nullptr);
  fs::permissions(dir / "ro", fs::perms::owner_all);
  EXPECT_EQ(builds_, 2);
  const std::string text = warnings_.str();
  EXPECT_NE(text.find("warning: oracle cache not written"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2) << text;  // one per cache object
}

TEST_F(OracleCacheTest, OffBuildsAndWritesNothing) {
  TempDir dir;
  OracleCacheSettings settings;
  settings.enabled = false;
  settings.folder = dir.path();
  OracleCache cache(settings, &warnings_);
  EXPECT_TRUE(cache.folder().empty());
  cache.Get(jaws_->lower_L, jaws_->upper_U, options_,
            [&] { return Build(jaws_->lower_L, options_); });
  EXPECT_EQ(cache.last_outcome(), OracleCacheOutcome::kOff);
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

// Byte entries: the bytes come back as put; a truncated, extended, flipped, foreign or
// other-key entry is refused with one warning line naming the file and the trouble (and
// replaced by the next put); names check their kind.
TEST(OracleCacheBytesTest, BytesComeBackAsPutAndDamageIsRefusedWithOneLine) {
  TempDir dir;
  std::ostringstream warnings;
  OracleCacheSettings settings;
  settings.folder = dir.path();
  OracleCache cache(settings, &warnings);
  const std::string bytes = std::string("an analysis\0with a zero", 24) + std::string(1000, 'x');
  EXPECT_FALSE(cache.GetBytes("analysis", 7).has_value());  // missing: no warning
  cache.PutBytes("analysis", 7, bytes);
  const fs::path entry = dir / ByteEntryName("analysis", 7);
  ASSERT_TRUE(fs::exists(entry));
  EXPECT_EQ(cache.GetBytes("analysis", 7), bytes);
  EXPECT_FALSE(cache.GetBytes("analysis", 8).has_value());  // another key: another file
  EXPECT_TRUE(warnings.str().empty()) << warnings.str();

  const std::string file = ByteEntryFile(7, bytes);
  std::string flipped = file;
  flipped[file.size() - 10] ^= 1;
  std::string other_format = file;
  other_format[8] = 2;
  const std::vector<std::pair<std::string, std::string>> damaged = {
      {file.substr(0, file.size() - 1), "truncated"},
      {file + "y", "extended"},
      {flipped, "checksum"},
      {other_format, "format 2"},
      {ByteEntryFile(8, bytes), "another key"},
      {"OCCLORCL not ours", "no header"}};
  for (const auto& [content, trouble] : damaged) {
    std::ofstream(entry, std::ios::binary | std::ios::trunc) << content;
    warnings.str("");
    EXPECT_FALSE(cache.GetBytes("analysis", 7).has_value()) << trouble;
    const std::string text = warnings.str();
    EXPECT_NE(text.find(entry.string()), std::string::npos) << text;
    EXPECT_NE(text.find(trouble), std::string::npos) << text;
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
    EXPECT_THROW(ByteEntryBytes(7, content), std::runtime_error) << trouble;
  }
  cache.PutBytes("analysis", 7, bytes);
  EXPECT_EQ(cache.GetBytes("analysis", 7), bytes);
  EXPECT_EQ(ByteEntryBytes(7, ByteEntryFile(7, "")), "");

  EXPECT_EQ(ByteEntryName("analysis", 0xabc), "analysis-0000000000000abc.occo");
  for (const char* bad : {"", "oracle", "Analysis", "an-alysis", "a1"})
    EXPECT_THROW(ByteEntryName(bad, 1), std::invalid_argument) << bad;
}

TEST(OracleCacheBytesTest, OffOrUnwritableIsNothingOrOneWarning) {
  TempDir dir;
  std::ostringstream warnings;
  OracleCacheSettings off;
  off.enabled = false;
  off.folder = dir.path();
  OracleCache none(off, &warnings);
  none.PutBytes("analysis", 1, "x");
  EXPECT_FALSE(none.GetBytes("analysis", 1).has_value());
  EXPECT_TRUE(fs::is_empty(dir.path()));
  // A folder under a regular file cannot be made, by root either.
  std::ofstream(dir / "file") << "x";
  OracleCacheSettings blocked;
  blocked.folder = dir / "file" / "cache";
  OracleCache cache(blocked, &warnings);
  for (int i = 0; i < 3; ++i) {
    cache.PutBytes("analysis", 1, "x");
    EXPECT_FALSE(cache.GetBytes("analysis", 1).has_value());
  }
  const std::string text = warnings.str();
  EXPECT_NE(text.find("warning: oracle cache not written"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
}

// Several threads putting and getting the same entries at once: every get is either nothing or
// the bytes put, never a part, and no warning (no entry is ever seen half-written).
TEST(OracleCacheBytesTest, ConcurrentPutsAndGetsSeeWholeEntriesOnly) {
  TempDir dir;
  std::ostringstream warnings;
  OracleCacheSettings settings;
  settings.folder = dir.path();
  OracleCache cache(settings, &warnings);
  const std::string bytes(200000, 'b');
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 20; ++i) {
        if ((i + t) % 2 == 0) cache.PutBytes("analysis", 3, bytes);
        const auto got = cache.GetBytes("analysis", 3);
        if (got && *got != bytes) ++wrong;
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(wrong.load(), 0);
  EXPECT_TRUE(warnings.str().empty()) << warnings.str();
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1u);  // no temporary file left
}

TEST_F(OracleCacheTest, EvictionCountsByteEntriesAndKeepsForeignFiles) {
  TempDir dir;
  OracleCacheOutcome outcome;
  Get(dir.path(), &outcome);
  const fs::path oracle = EntryOf(dir.path());
  const auto now = fs::file_time_type::clock::now();
  OracleCacheSettings settings;
  settings.folder = dir.path();
  OracleCache cache(settings, &warnings_);
  cache.PutBytes("analysis", 1, std::string(1000, 'a'));
  cache.PutBytes("analysis", 2, std::string(1000, 'a'));
  const fs::path older = dir / ByteEntryName("analysis", 1);
  const fs::path newer = dir / ByteEntryName("analysis", 2);
  fs::last_write_time(older, now - std::chrono::hours(3));
  fs::last_write_time(newer, now - std::chrono::hours(2));
  fs::last_write_time(oracle, now - std::chrono::hours(1));
  const fs::path foreign = dir / ByteEntryName("analysis", 3);
  std::ofstream(foreign) << "not an entry";
  fs::last_write_time(foreign, now - std::chrono::hours(10));
  // Room for the oracle and one byte entry: the older byte entry goes.
  EvictOracleCache(dir.path(), fs::file_size(oracle) + fs::file_size(newer), "");
  EXPECT_FALSE(fs::exists(older));
  EXPECT_TRUE(fs::exists(newer));
  EXPECT_TRUE(fs::exists(oracle));
  EXPECT_TRUE(fs::exists(foreign));
}

}  // namespace
}  // namespace occlude::app
