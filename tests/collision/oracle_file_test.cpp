// Saved oracles (oracle_file.h): a loaded oracle answers bit-identically to the built one at
// every level; truncated, corrupt, foreign, older and mismatched bytes are all rejected with
// their reason; the cache key changes with any mesh byte or option field; the oracle's
// answers are the same for any build thread count and without the tree-pair structures.
#include "occlude/collision/oracle_file.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "occlude/io/content_hash.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

using MeshPtr = std::shared_ptr<const io::TriangleMesh>;

// A small synthetic bite, built once: 0.3 mm voxels keep it fast and still use the half-voxel
// field bound (FieldBoundSplit(0.3) = 2, its four levels).
class OracleFileTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    io::SyntheticJawOptions o;
    o.triangles_per_jaw = 5000;
    jaws_ = new io::SyntheticJawPair(io::MakeSyntheticJawPair(o));
    lower_ = std::make_shared<const io::TriangleMesh>(jaws_->lower_L);
    upper_ = std::make_shared<const io::TriangleMesh>(jaws_->upper_U);
    options_.voxel_size_mm = 0.3;
    built_ = new JawOracle(lower_, upper_, options_);
    bytes_ = new std::string(SaveOracle(*built_));
  }
  static void TearDownTestSuite() {
    delete bytes_;
    delete built_;
    delete jaws_;
    lower_.reset();
    upper_.reset();
  }

  // The hash of every answer at poses about the bite (pushed in, at it, opened; small random
  // rotations, fixed seed), at every level, with and without residuals.
  static std::uint64_t AnswersDigest(const JawOracle& oracle) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> angle(-0.02, 0.02);
    io::Hasher64 hash;
    for (int i = 0; i < 12; ++i) {
      const double offset = -0.3 + 0.08 * i;
      const Eigen::Isometry3d X = Eigen::Translation3d(offset * jaws_->occlusal_axis_L) *
                                  Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitX()) *
                                  Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitZ()) *
                                  jaws_->X_LU;
      for (const AccuracyLevel level :
           {AccuracyLevel::kVoxel, AccuracyLevel::kSubVoxel, AccuracyLevel::kExact}) {
        for (const bool residuals : {false, true}) {
          OracleRequest request;
          request.level = level;
          request.residuals = residuals;
          OracleResult result;
          oracle.Query(X, request, &result);
          HashOracleResult(result, &hash);
        }
      }
    }
    return hash.Finish();
  }

  static OracleFileProblem ProblemOf(std::string_view bytes) {
    try {
      LoadOracle(bytes, lower_, upper_, options_);
    } catch (const OracleFileError& e) {
      EXPECT_NE(std::string(e.what()), "");
      return e.problem();
    }
    ADD_FAILURE() << "loaded " << bytes.size() << " bytes that should have been rejected";
    return OracleFileProblem::kForeign;
  }

  static io::SyntheticJawPair* jaws_;
  static MeshPtr lower_, upper_;
  static OracleOptions options_;
  static JawOracle* built_;
  static std::string* bytes_;
};
io::SyntheticJawPair* OracleFileTest::jaws_ = nullptr;
MeshPtr OracleFileTest::lower_, OracleFileTest::upper_;
OracleOptions OracleFileTest::options_;
JawOracle* OracleFileTest::built_ = nullptr;
std::string* OracleFileTest::bytes_ = nullptr;

TEST_F(OracleFileTest, LoadedOracleAnswersBitIdenticallyAtEveryLevel) {
  const JawOracle loaded = LoadOracle(*bytes_, lower_, upper_, options_);
  EXPECT_EQ(loaded.num_samples(), built_->num_samples());
  // The file holds what the oracle holds in memory, and little else.
  EXPECT_LE(static_cast<double>(bytes_->size()),
            1.05 * static_cast<double>(built_->MemoryBytes()) + 1e5)
      << "bytes " << bytes_->size() << ", in memory " << built_->MemoryBytes();
  EXPECT_EQ(AnswersDigest(loaded), AnswersDigest(*built_));
  // Saving the loaded oracle gives the same sections again (the same structures).
  const std::vector<OracleFileSection> a = DescribeOracleBytes(*bytes_);
  const std::string again = SaveOracle(loaded);
  const std::vector<OracleFileSection> b = DescribeOracleBytes(again);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].tag, b[i].tag);
    EXPECT_EQ(a[i].size, b[i].size) << a[i].tag;
  }
}

TEST_F(OracleFileTest, FileRoundTripLeavesNoTemporaryFileAndAMissingFileIsUnreadable) {
  const test::TempDir dir;
  SaveOracleFile(*built_, dir / "a.oracle");
  {  // written section by section, the file holds exactly SaveOracle's bytes
    std::ifstream in(dir / "a.oracle", std::ios::binary);
    const std::string file_bytes((std::istreambuf_iterator<char>(in)),
                                 std::istreambuf_iterator<char>());
    EXPECT_TRUE(file_bytes == *bytes_) << file_bytes.size() << " vs " << bytes_->size();
  }
  const JawOracle loaded = LoadOracleFile(dir / "a.oracle", lower_, upper_, options_);
  EXPECT_EQ(AnswersDigest(loaded), AnswersDigest(*built_));
  // With the key given (from the meshes' hashes): the same oracle; another key is a mismatch.
  const std::uint64_t key =
      OracleCacheKey(io::MeshContentHash(*lower_), io::MeshContentHash(*upper_), options_);
  EXPECT_EQ(key, OracleCacheKey(*lower_, *upper_, options_));
  EXPECT_EQ(AnswersDigest(LoadOracleFile(dir / "a.oracle", lower_, upper_, options_, key)),
            AnswersDigest(*built_));
  try {
    LoadOracleFile(dir / "a.oracle", lower_, upper_, options_, key ^ 1);
    FAIL() << "loaded under another key";
  } catch (const OracleFileError& e) {
    EXPECT_EQ(e.problem(), OracleFileProblem::kMismatch);
  }
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path()))
    ++files;
  EXPECT_EQ(files, 1u);
  try {
    LoadOracleFile(dir / "missing.oracle", lower_, upper_, options_);
    FAIL() << "a missing file loaded";
  } catch (const OracleFileError& e) {
    EXPECT_EQ(e.problem(), OracleFileProblem::kUnreadable);
    EXPECT_NE(std::string(e.what()).find("missing.oracle"), std::string::npos) << e.what();
  }
}

TEST_F(OracleFileTest, TruncatedAtEverySectionBoundaryAndAtRandomOffsetsIsRejected) {
  std::vector<std::size_t> cuts = {0, 1, 7, 8, 47};
  for (const OracleFileSection& s : DescribeOracleBytes(*bytes_)) {
    for (const std::size_t at : {s.offset, s.offset + 1, s.offset + 16, s.offset + s.size - 1})
      cuts.push_back(at);
  }
  std::mt19937 rng(3);
  std::uniform_int_distribution<std::size_t> any(0, bytes_->size() - 1);
  for (int i = 0; i < 40; ++i) cuts.push_back(any(rng));
  for (const std::size_t cut : cuts) {
    EXPECT_EQ(ProblemOf(std::string_view(*bytes_).substr(0, cut)), OracleFileProblem::kTruncated)
        << cut;
  }
}

TEST_F(OracleFileTest, AFlippedByteInAnySectionIsRejected) {
  std::string bytes = *bytes_;  // flipped in place and back
  for (const OracleFileSection& s : DescribeOracleBytes(*bytes_)) {
    for (const std::size_t at : {s.offset + 12, s.offset + s.size / 2, s.offset + s.size - 1}) {
      bytes[at] = static_cast<char>(bytes[at] ^ 0x10);
      // In the header, byte 12 is the section count (covered by the header's checksum).
      EXPECT_EQ(ProblemOf(bytes), OracleFileProblem::kCorrupt) << s.tag << " byte " << at;
      bytes[at] = (*bytes_)[at];
    }
  }
  bytes += 'x';  // a byte too many
  EXPECT_EQ(ProblemOf(bytes), OracleFileProblem::kCorrupt);
}

TEST_F(OracleFileTest, ForeignBytesAndOtherVersionsAreRejected) {
  EXPECT_EQ(ProblemOf("solid occlude\nendsolid occlude\n"), OracleFileProblem::kForeign);
  std::string bytes = *bytes_;
  bytes[0] = 'X';
  EXPECT_EQ(ProblemOf(bytes), OracleFileProblem::kForeign);
  for (const std::uint32_t version : {kOracleFileVersion - 1, kOracleFileVersion + 1}) {
    bytes = *bytes_;
    std::memcpy(&bytes[8], &version, sizeof(version));
    EXPECT_EQ(ProblemOf(bytes), OracleFileProblem::kVersion) << version;
  }
}

TEST_F(OracleFileTest, OtherMeshesOrOptionsAreAMismatch) {
  OracleOptions other = options_;
  other.voxel_size_mm = 0.25;
  EXPECT_THROW(
      {
        try {
          LoadOracle(*bytes_, lower_, upper_, other);
        } catch (const OracleFileError& e) {
          EXPECT_EQ(e.problem(), OracleFileProblem::kMismatch);
          throw;
        }
      },
      OracleFileError);
  auto moved = std::make_shared<io::TriangleMesh>(*upper_);
  moved->vertices[0].x() += 1e-9;
  try {
    LoadOracle(*bytes_, lower_, moved, options_);
    FAIL() << "loaded for another upper mesh";
  } catch (const OracleFileError& e) {
    EXPECT_EQ(e.problem(), OracleFileProblem::kMismatch);
  }
  other = options_;
  other.threads = 3;  // never changes what is built
  EXPECT_NO_THROW(LoadOracle(*bytes_, lower_, upper_, other));
  EXPECT_THROW(LoadOracle(*bytes_, nullptr, upper_, options_), std::invalid_argument);
}

TEST_F(OracleFileTest, KeyChangesWithAnyMeshBitOrOptionField) {
  const std::uint64_t key = OracleCacheKey(*lower_, *upper_, options_);
  const std::vector<std::function<void(OracleOptions*)>> changes = {
      [](OracleOptions* o) { o->voxel_size_mm = 0.2; },
      [](OracleOptions* o) { o->sample_spacing_mm = 0.25; },
      [](OracleOptions* o) { o->sdf_dilation_voxels = 3; },
      [](OracleOptions* o) { o->cell_level = 2; },
      [](OracleOptions* o) { o->lower_level = 0; },
      [](OracleOptions* o) { o->distance_bound = false; },
      [](OracleOptions* o) { o->field_bound_mm = 0.15; },
      [](OracleOptions* o) { o->field_bound_depth_mm = 0.2; },
      [](OracleOptions* o) { o->arch = ArchFrame(); },
      [](OracleOptions* o) { o->tree_queries = false; },
  };
  for (std::size_t i = 0; i < changes.size(); ++i) {
    OracleOptions o = options_;
    changes[i](&o);
    EXPECT_NE(OracleCacheKey(*lower_, *upper_, o), key) << "option change " << i;
  }
  OracleOptions with_arch = options_;
  with_arch.arch = ArchFrame();
  const std::uint64_t arch_key = OracleCacheKey(*lower_, *upper_, with_arch);
  for (int field = 0; field < 13; ++field) {
    OracleOptions o = with_arch;
    ArchFrame& a = *o.arch;
    Eigen::Vector3d* vectors[] = {&a.origin_L, &a.occlusal_L, &a.anterior_L, &a.lateral_L};
    if (field < 12) {
      (*vectors[field / 3])[field % 3] += 1e-12;
    } else {
      a.anterior_split_mm += 1e-12;
    }
    EXPECT_NE(OracleCacheKey(*lower_, *upper_, o), arch_key) << "arch field " << field;
  }
  OracleOptions threads = options_;
  threads.threads = 5;
  EXPECT_EQ(OracleCacheKey(*lower_, *upper_, threads), key);
  io::TriangleMesh lower = *lower_;
  lower.triangles[0][1] ^= 1;  // one bit of one index
  EXPECT_NE(OracleCacheKey(lower, *upper_, options_), key);
  io::TriangleMesh upper = *upper_;
  upper.vertices.back().z() = std::nextafter(upper.vertices.back().z(), 1e9);
  EXPECT_NE(OracleCacheKey(*lower_, upper, options_), key);
}

TEST_F(OracleFileTest, AnswersAreTheSameForAnyBuildThreadCount) {
  for (const int threads : {1, 3}) {  // built_ has 0: every core
    OracleOptions o = options_;
    o.threads = threads;
    EXPECT_EQ(AnswersDigest(JawOracle(lower_, upper_, o)), AnswersDigest(*built_)) << threads;
  }
}

// Without the structures only tree-pair queries read (OracleOptions::tree_queries), the oracle
// answers bit-identically at every level, holds less, and saves and loads as itself.
TEST_F(OracleFileTest, WithoutTreeQueryStructuresAnswersAlikeInLessMemory) {
  OracleOptions o = options_;
  o.tree_queries = false;
  const JawOracle lean(lower_, upper_, o);
  EXPECT_EQ(AnswersDigest(lean), AnswersDigest(*built_));
  EXPECT_TRUE(lean.lower_tree().explicit_spheres().empty());
  EXPECT_TRUE(lean.upper_tree().explicit_spheres().empty());
  EXPECT_TRUE(lean.upper_tree().distance_bound().empty());
  EXPECT_FALSE(lean.lower_tree().distance_bound().empty());  // the oracle reads it
  EXPECT_FALSE(built_->lower_tree().explicit_spheres().empty());
  EXPECT_LT(lean.MemoryBytes(), built_->MemoryBytes());
  const JawOracle loaded = LoadOracle(SaveOracle(lean), lower_, upper_, o);
  EXPECT_EQ(AnswersDigest(loaded), AnswersDigest(*built_));
  // A file of the full oracle is not taken for the lean one, nor the other way round.
  EXPECT_THROW(LoadOracle(*bytes_, lower_, upper_, o), OracleFileError);
}

}  // namespace
}  // namespace occlude::collision
