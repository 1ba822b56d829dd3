// The case analysis on the small synthetic pair: its designed relationships at the designed bite
// from detected landmarks, a known sagittal shift of the upper jaw moving the molar offsets
// by that shift, given landmarks winning over detected ones, and the given upper
// landmarks following the pair re-expressed at its reference.
#include "session/case_analysis.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>
#include <string>
#include <vector>

#include "base/user_error.h"
#include "config/case_config.h"
#include "occlude/io/landmark_file.h"
#include "occlude/io/synthetic_jaws.h"
#include "session/case_session.h"
#include "test_common.h"

namespace occlude::test {
namespace {

using io::Jaw;
using io::LandmarkType;

constexpr std::size_t kTriangles = 20000;
constexpr std::uint32_t kSeed = 1;
// The analysis's targets for relationships from detected landmarks (docs/results/analysis).
constexpr double kIncisorTargetMm = 0.5;
constexpr double kSideTargetMm = 1.0;
// The landmark frame is a plane fit through both jaws' occlusal landmarks: a shift of the upper
// jaw tilts it slightly, which moves a measure by at most this much.
constexpr double kFrameFitMm = 0.05;

struct Fixture {
  app::JawPair pair = app::SyntheticJawPair(kTriangles, kSeed);
  io::SyntheticJawPair design = io::MakeSyntheticJawPair({kTriangles, kSeed});
};

const Fixture& Synthetic() {
  static const Fixture f;
  return f;
}

const app::CaseAnalysis& Detected() {
  static const app::CaseAnalysis a = app::AnalyzeCase(Synthetic().pair);
  return a;
}

double Mm(const analysis::Measure& m) {
  EXPECT_TRUE(m.mm.has_value()) << m.note;
  return m.mm.value_or(NAN);
}

TEST(CaseAnalysisTest, DetectedLandmarksGiveTheDesignedRelationshipsAtTheBite) {
  const app::CaseAnalysis& a = Detected();
  ASSERT_TRUE(a.lower_L.ok()) << a.lower_L.error;
  ASSERT_TRUE(a.upper_U.ok()) << a.upper_U.error;
  EXPECT_FALSE(a.has_given_landmarks);
  const analysis::Relationships r = app::RelationshipsAt(a, Synthetic().pair.X_LU_ref);
  const io::SyntheticRelationships& d = Synthetic().design.relationships;
  EXPECT_NEAR(Mm(r.overjet), d.overjet_mm, kIncisorTargetMm);
  EXPECT_NEAR(Mm(r.overbite), d.overbite_mm, kIncisorTargetMm);
  EXPECT_NEAR(Mm(r.midline_deviation), d.midline_deviation_mm, kIncisorTargetMm);
  EXPECT_NEAR(Mm(r.molar[0].offset), d.molar_mm.right, kSideTargetMm);
  EXPECT_NEAR(Mm(r.molar[1].offset), d.molar_mm.left, kSideTargetMm);
  for (const analysis::SideRelationship& s : {r.molar[0], r.molar[1]}) {
    EXPECT_EQ(s.occlusion_class, analysis::OcclusionClass::kI);
  }
  EXPECT_TRUE(r.crossbite.empty());
}

TEST(CaseAnalysisTest, ASagittalShiftMovesTheMolarOffsetsByTheShift) {
  const app::CaseAnalysis& a = Detected();
  const Eigen::Isometry3d& X_LU = Synthetic().pair.X_LU_ref;
  const analysis::Relationships before = app::RelationshipsAt(a, X_LU);
  for (const double shift_mm : {-1.0, 2.0, 4.0}) {
    const Eigen::Vector3d shift_L = shift_mm * before.frame_L.anterior_J;
    const Eigen::Isometry3d X_shifted = Eigen::Translation3d(shift_L) * X_LU;
    const analysis::Relationships after = app::RelationshipsAt(a, X_shifted);
    for (const int side : {0, 1}) {
      EXPECT_NEAR(Mm(after.molar[side].offset) - Mm(before.molar[side].offset), shift_mm,
                  kFrameFitMm)
          << "side " << side << ", shift " << shift_mm;
    }
    EXPECT_NEAR(Mm(after.overjet) - Mm(before.overjet), shift_mm, kFrameFitMm);
    EXPECT_NEAR(Mm(after.midline_deviation), Mm(before.midline_deviation), kFrameFitMm);
  }
}

TEST(CaseAnalysisTest, GivenLandmarksWinOverDetectedOnes) {
  const Fixture& f = Synthetic();
  const app::CaseAnalysis a = app::AnalyzeCase(f.pair, f.design.landmarks);
  EXPECT_TRUE(a.has_given_landmarks);
  std::size_t given = 0;
  for (const auto* jaw : {&a.lower_L, &a.upper_U}) {
    for (const analysis::ArchLandmark& l : jaw->landmarks) {
      if (l.source == analysis::LandmarkSource::kGiven) ++given;
    }
  }
  EXPECT_EQ(given, f.design.landmarks.size());
  for (const io::Landmark& want : f.design.landmarks) {
    const analysis::ArchAnalysis& jaw = want.jaw == Jaw::kUpper ? a.upper_U : a.lower_L;
    const analysis::ArchLandmark* l = jaw.Find(want.tooth_fdi, want.type);
    ASSERT_NE(l, nullptr);
    EXPECT_EQ(l->source, analysis::LandmarkSource::kGiven);
    EXPECT_LT((l->landmark.p - want.p).norm(), kExactMm);
  }
  // The designed landmarks give the designed relationships (clinical.md's definitions).
  const analysis::Relationships r = app::RelationshipsAt(a, f.pair.X_LU_ref);
  const io::SyntheticRelationships& d = f.design.relationships;
  EXPECT_EQ(r.frame_source, "landmarks");
  EXPECT_NEAR(Mm(r.overjet), d.overjet_mm, kFrameFitMm);
  EXPECT_NEAR(Mm(r.overbite), d.overbite_mm, kFrameFitMm);
  EXPECT_NEAR(Mm(r.molar[0].offset), d.molar_mm.right, kFrameFitMm);
  EXPECT_NEAR(Mm(r.canine[1].offset), d.canine_mm.left, kFrameFitMm);
}

TEST(CaseAnalysisTest, OneGivenLandmarkReplacesOnlyItsDetectedOne) {
  const app::CaseAnalysis& detected = Detected();
  const analysis::ArchLandmark* edge = detected.upper_U.Find(11, LandmarkType::kIncisalEdge);
  ASSERT_NE(edge, nullptr);
  io::Landmark moved = edge->landmark;
  moved.p += Eigen::Vector3d(0.0, 0.0, 1.0);  // 1 mm anterior in U (z of the synthetic pair)
  const app::CaseAnalysis a = app::AnalyzeCase(Synthetic().pair, {moved});
  EXPECT_EQ(a.upper_U.landmarks.size(), detected.upper_U.landmarks.size());
  EXPECT_EQ(a.lower_L.landmarks.size(), detected.lower_L.landmarks.size());
  const analysis::ArchLandmark* l = a.upper_U.Find(11, LandmarkType::kIncisalEdge);
  ASSERT_NE(l, nullptr);
  EXPECT_EQ(l->source, analysis::LandmarkSource::kGiven);
  EXPECT_LT((l->landmark.p - moved.p).norm(), kExactMm);
  for (const analysis::ArchLandmark& x : a.lower_L.landmarks) {
    EXPECT_EQ(x.source, analysis::LandmarkSource::kDetected);
  }
  // Overjet is the mean of the two central incisors: one of them 1 mm forward adds 0.5 mm.
  const Eigen::Isometry3d& X_LU = Synthetic().pair.X_LU_ref;
  EXPECT_NEAR(
      Mm(app::RelationshipsAt(a, X_LU).overjet) - Mm(app::RelationshipsAt(detected, X_LU).overjet),
      0.5, kFrameFitMm);
}

TEST(CaseAnalysisTest, GivenUpperLandmarksFollowThePairAtItsReference) {
  const Fixture& f = Synthetic();
  const app::JawPair at_ref = app::AtReference(f.pair);
  const std::vector<io::Landmark> given =
      app::GivenAtReference(f.pair.X_LU_ref, f.design.landmarks);
  ASSERT_EQ(given.size(), f.design.landmarks.size());
  const analysis::Relationships moved =
      app::RelationshipsAt(app::AnalyzeCase(at_ref, given), Eigen::Isometry3d::Identity());
  const analysis::Relationships original =
      app::RelationshipsAt(app::AnalyzeCase(f.pair, f.design.landmarks), f.pair.X_LU_ref);
  EXPECT_NEAR(Mm(moved.overjet), Mm(original.overjet), kExactMm * 1e3);
  EXPECT_NEAR(Mm(moved.molar[0].offset), Mm(original.molar[0].offset), kExactMm * 1e3);
  EXPECT_NEAR(Mm(moved.midline_deviation), Mm(original.midline_deviation), kExactMm * 1e3);
}

// A synthetic case config naming `landmarks` (text) as its [landmarks] file.
app::CaseConfig ConfigWithLandmarks(const TempDir& tmp, const std::string& landmarks) {
  std::ofstream(tmp / "given.csv") << landmarks;
  std::ofstream(tmp / "case.toml")
      << "[synthetic]\ntriangles = " << kTriangles << "\nseed = " << kSeed
      << "\n[landmarks]\nfile = \"given.csv\"\n";
  return app::LoadCaseConfig(tmp / "case.toml");
}

TEST(CaseAnalysisTest, TheSessionAppliesTheConfigsLandmarksMovedWithTheUpperJaw) {
  TempDir tmp;
  const Fixture& f = Synthetic();
  app::CaseSession session(ConfigWithLandmarks(tmp, io::FormatLandmarkFile(f.design.landmarks)));
  const app::CaseAnalysis& a = session.Analysis();
  EXPECT_TRUE(a.has_given_landmarks);
  // The session works at the reference: the designed bite is X_LU = identity.
  const analysis::Relationships r = app::RelationshipsAt(a, Eigen::Isometry3d::Identity());
  const io::SyntheticRelationships& d = f.design.relationships;
  EXPECT_NEAR(Mm(r.overjet), d.overjet_mm, kFrameFitMm);
  EXPECT_NEAR(Mm(r.overbite), d.overbite_mm, kFrameFitMm);
  EXPECT_NEAR(Mm(r.molar[1].offset), d.molar_mm.left, kFrameFitMm);
}

TEST(CaseAnalysisTest, ABadLandmarkFileIsOneLineNamingFileLineAndField) {
  TempDir tmp;
  try {
    app::CaseSession session(
        ConfigWithLandmarks(tmp, "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,41,mesial,0,0,0\n"));
    ADD_FAILURE() << "no error";
  } catch (const app::UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("given.csv: line 2"), std::string::npos) << what;
    EXPECT_NE(what.find("tooth"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace occlude::test
