// The arch analysis as a cache entry (session/analysis_entry.h): it decodes to the analysis bit
// for bit on both synthetic jaws (and on a scanned case when ../shared/data is there); any
// malformed entry throws; the key changes with a mesh byte, the jaw and every option; and
// AnalyzeJaw through a cache answers as the analysis itself, from a hit, and after a bad entry.
#include "session/analysis_entry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "session/case_analysis.h"
#include "session/jaw_pair.h"
#include "session/oracle_cache.h"
#include "test_common.h"

namespace occlude::app {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

const JawPair& Synthetic() {
  static const JawPair pair = AtReference(SyntheticJawPair(20000, 1));
  return pair;
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool SameBits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return SameBits(a.x(), b.x()) && SameBits(a.y(), b.y()) && SameBits(a.z(), b.z());
}

// Every field of two analyses, doubles compared by their bits.
void ExpectIdentical(const analysis::ArchAnalysis& a, const analysis::ArchAnalysis& b) {
  EXPECT_EQ(a.jaw, b.jaw);
  EXPECT_EQ(a.error, b.error);
  EXPECT_TRUE(SameBits(a.frame.origin_J, b.frame.origin_J));
  EXPECT_TRUE(SameBits(a.frame.lateral_J, b.frame.lateral_J));
  EXPECT_TRUE(SameBits(a.frame.anterior_J, b.frame.anterior_J));
  EXPECT_TRUE(SameBits(a.frame.occlusal_J, b.frame.occlusal_J));
  ASSERT_EQ(a.arch_curve_J.size(), b.arch_curve_J.size());
  for (std::size_t i = 0; i < a.arch_curve_J.size(); ++i)
    EXPECT_TRUE(SameBits(a.arch_curve_J[i], b.arch_curve_J[i])) << i;
  EXPECT_TRUE(SameBits(a.midline_J, b.midline_J));
  ASSERT_EQ(a.teeth.size(), b.teeth.size());
  for (std::size_t i = 0; i < a.teeth.size(); ++i) {
    const analysis::ArchTooth &s = a.teeth[i], &t = b.teeth[i];
    EXPECT_EQ(s.fdi, t.fdi);
    EXPECT_TRUE(SameBits(s.centre_J, t.centre_J));
    EXPECT_EQ(s.source, t.source);
    EXPECT_TRUE(SameBits(s.mesial_mm, t.mesial_mm) && SameBits(s.distal_mm, t.distal_mm) &&
                SameBits(s.confidence, t.confidence))
        << s.fdi;
  }
  ASSERT_EQ(a.landmarks.size(), b.landmarks.size());
  for (std::size_t i = 0; i < a.landmarks.size(); ++i) {
    const analysis::ArchLandmark &s = a.landmarks[i], &t = b.landmarks[i];
    EXPECT_EQ(s.landmark.jaw, t.landmark.jaw);
    EXPECT_EQ(s.landmark.tooth_fdi, t.landmark.tooth_fdi);
    EXPECT_EQ(s.landmark.type, t.landmark.type);
    EXPECT_TRUE(SameBits(s.landmark.p, t.landmark.p));
    EXPECT_EQ(s.source, t.source);
    EXPECT_TRUE(SameBits(s.confidence, t.confidence));
    EXPECT_EQ(s.method, t.method);
  }
  EXPECT_EQ(a.notes, b.notes);
}

TEST(AnalysisEntryTest, DecodesToTheAnalysisBitForBit) {
  for (const io::Jaw jaw : {io::Jaw::kLower, io::Jaw::kUpper}) {
    const auto& mesh = jaw == io::Jaw::kLower ? *Synthetic().lower_L : *Synthetic().upper_U;
    const analysis::ArchAnalysis a = analysis::AnalyzeArch(mesh, jaw);
    ASSERT_TRUE(a.ok()) << a.error;
    ASSERT_FALSE(a.landmarks.empty());
    ExpectIdentical(a, DecodeArchAnalysis(EncodeArchAnalysis(a)));
  }
  // Awkward values: negative zero, subnormal, the largest, a failed jaw's error and notes.
  analysis::ArchAnalysis odd;
  odd.error = "no tooth found \"here\"\n";
  odd.frame.origin_J = {-0.0, 4.9e-324, 1.7976931348623157e308};
  odd.midline_J = {0.1, 1.0 / 3.0, -2.5e-17};
  odd.notes = {"a", "", "ü"};
  ExpectIdentical(odd, DecodeArchAnalysis(EncodeArchAnalysis(odd)));
}

TEST(AnalysisEntryTest, DecodesAScannedCaseBitForBit) {
  OCCLUDE_REQUIRE_CASE(dir, "a-bite-3shape");
  const JawPair pair = LoadCaseFolder(dir, "a case folder");
  const analysis::ArchAnalysis a = analysis::AnalyzeArch(*pair.upper_U, io::Jaw::kUpper);
  ExpectIdentical(a, DecodeArchAnalysis(EncodeArchAnalysis(a)));
}

TEST(AnalysisEntryTest, MalformedEntriesThrow) {
  analysis::ArchAnalysis a = analysis::AnalyzeArch(*Synthetic().lower_L, io::Jaw::kLower);
  const std::string good = EncodeArchAnalysis(a);
  std::vector<std::string> bad = {"", "{}", good.substr(0, good.size() / 2), "[1, 2]",
                                  R"({"jaw": 5, "error": ""})"};
  // A non-finite coordinate is written as null, which does not read back.
  a.midline_J.x() = std::numeric_limits<double>::quiet_NaN();
  bad.push_back(EncodeArchAnalysis(a));
  for (const std::string& text : bad) {
    EXPECT_THROW(DecodeArchAnalysis(text), std::runtime_error) << text.substr(0, 80);
  }
  // An unknown landmark type.
  std::string type = good;
  const std::size_t at = type.find("\"landmarks\":[[");
  ASSERT_NE(at, std::string::npos);
  const std::size_t third = type.find(',', type.find(',', at + 14) + 1) + 1;  // the type field
  type.replace(third, type.find(',', third) - third, "99");
  EXPECT_THROW(DecodeArchAnalysis(type), std::runtime_error);
}

TEST(AnalysisEntryTest, TheKeyChangesWithAMeshByteTheJawAndEveryOption) {
  const io::TriangleMesh& mesh = *Synthetic().lower_L;
  const analysis::ArchAnalysisOptions options;
  const std::uint64_t key = ArchAnalysisKey(mesh, io::Jaw::kLower, options);
  EXPECT_EQ(key, ArchAnalysisKey(io::TriangleMesh(mesh), io::Jaw::kLower, options));
  io::TriangleMesh moved = mesh;
  moved.vertices[7].x() = std::nextafter(moved.vertices[7].x(), 1e9);
  EXPECT_NE(key, ArchAnalysisKey(moved, io::Jaw::kLower, options));
  EXPECT_NE(key, ArchAnalysisKey(mesh, io::Jaw::kUpper, options));
  for (double analysis::ArchAnalysisOptions::*field :
       {&analysis::ArchAnalysisOptions::grid_mm, &analysis::ArchAnalysisOptions::curve_step_mm,
        &analysis::ArchAnalysisOptions::crown_depth_mm}) {
    analysis::ArchAnalysisOptions other = options;
    other.*field *= 1.5;
    EXPECT_NE(key, ArchAnalysisKey(mesh, io::Jaw::kLower, other));
  }
  const std::string version = analysis::ArchAnalysisCodeVersion();
  EXPECT_EQ(version.size(), 16u);
  EXPECT_EQ(version.find_first_not_of("0123456789abcdef"), std::string::npos) << version;
}

// Through a cache: a miss makes and saves, a hit reads it back, a corrupt entry is one warning
// and made again; every answer identical to the analysis without a cache.
TEST(AnalysisEntryTest, AnalyzeJawThroughACacheAnswersAsWithout) {
  TempDir dir;
  std::ostringstream warnings;
  OracleCacheSettings settings;
  settings.folder = dir.path();
  OracleCache cache(settings, &warnings);
  const io::TriangleMesh& mesh = *Synthetic().upper_U;
  const analysis::ArchAnalysis made = AnalyzeJaw(mesh, io::Jaw::kUpper, nullptr);
  const fs::path entry =
      dir / ByteEntryName(kArchAnalysisEntryKind, ArchAnalysisKey(mesh, io::Jaw::kUpper, {}));
  ExpectIdentical(made, AnalyzeJaw(mesh, io::Jaw::kUpper, &cache));  // miss
  ASSERT_TRUE(fs::exists(entry));
  ExpectIdentical(made, AnalyzeJaw(mesh, io::Jaw::kUpper, &cache));  // hit
  // A hit reads the entry: one whose analysis was changed (a valid entry of this key) is
  // answered from, so the entry, not a new analysis, answered above.
  analysis::ArchAnalysis marked = made;
  marked.notes.push_back("from the cache");
  cache.PutBytes(kArchAnalysisEntryKind, ArchAnalysisKey(mesh, io::Jaw::kUpper, {}),
                 EncodeArchAnalysis(marked));
  EXPECT_EQ(AnalyzeJaw(mesh, io::Jaw::kUpper, &cache).notes.back(), "from the cache");
  std::ofstream(entry, std::ios::binary | std::ios::trunc) << "damaged";
  ExpectIdentical(made, AnalyzeJaw(mesh, io::Jaw::kUpper, &cache));  // rebuilt
  EXPECT_NE(warnings.str().find("cache entry not used"), std::string::npos) << warnings.str();
  ExpectIdentical(made, AnalyzeJaw(mesh, io::Jaw::kUpper, &cache));  // and replaced
}

}  // namespace
}  // namespace occlude::app
