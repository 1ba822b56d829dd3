// The outputs of `occlude analyze` on the synthetic pair (5,000 triangles per jaw) at its designed
// bite: analysis.json holds the library's answer field by field (teeth, landmarks in L at the
// pose, relationships, frame), and landmarks.png shows a marker of the right kind (detected
// circle, given square) at every landmark, the markers of each arch an orthographic projection
// of the landmarks. (The command: tests/app/cli/cmd_analyze_test.cpp.)
#include "report/analysis_document.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "occlude/io/synthetic_jaws.h"
#include "report/report_images.h"
#include "test_common.h"

namespace occlude::test {
namespace {

using nlohmann::json;

constexpr std::size_t kTriangles = 5000;
// Markers are centred on the rounded pixel of a landmark and drawn 5 px wide.
constexpr int kMarkerWindowPx = 1;
// A least-squares fit of the pixels as an affine map of the points leaves at most this.
constexpr double kProjectionPx = 0.01;
constexpr double kJsonMm = 1e-9;

struct AnalysisFixture {
  app::JawPair pair = app::SyntheticJawPair(kTriangles, 1);
  io::SyntheticJawPair design = io::MakeSyntheticJawPair({kTriangles, 1});
  app::CaseAnalysis analysis;
  AnalysisFixture() {
    // Two given landmarks, one replacing a detected one and one of the upper jaw.
    std::vector<io::Landmark> given;
    for (const io::Landmark& l : design.landmarks) {
      if ((l.jaw == io::Jaw::kLower && l.tooth_fdi == 46 && l.type == io::LandmarkType::kMbCusp) ||
          (l.jaw == io::Jaw::kUpper && l.tooth_fdi == 11 &&
           l.type == io::LandmarkType::kIncisalEdge)) {
        given.push_back(l);
      }
    }
    analysis = app::AnalyzeCase(pair, given);
  }
  app::AnalysisInputs Inputs() const {
    app::AnalysisInputs in;
    in.case_name = pair.name;
    in.pose_source = "the designed bite";
    in.landmarks_source = "given.csv";
    in.jaws = &pair;
    in.analysis = &analysis;
    in.X_LU = pair.X_LU_ref;
    in.image_width_px = 900;
    return in;
  }
};

const AnalysisFixture& SharedAnalysis() {
  static const AnalysisFixture f;
  return f;
}

void ExpectVec(const json& j, const Eigen::Vector3d& v, double tol, const std::string& what) {
  ASSERT_TRUE(j.is_array() && j.size() == 3) << what;
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(j[i].get<double>(), v[i], tol) << what;
}

json AnalysisJsonOf(const app::AnalysisFiles& files) {
  for (const auto& [name, content] : files.files) {
    if (name == "analysis.json") return json::parse(content);
  }
  ADD_FAILURE() << "no analysis.json";
  return json();
}

TEST(AnalysisDocument, TheJsonHoldsTheLibrarysAnswerFieldByField) {
  const AnalysisFixture& f = SharedAnalysis();
  const app::AnalysisFiles files = app::MakeAnalysisFiles(f.Inputs());
  const json j = AnalysisJsonOf(files);
  const analysis::Relationships r = app::RelationshipsAt(f.analysis, f.pair.X_LU_ref);
  EXPECT_EQ(j["landmarks_file"], "given.csv");
  ExpectVec(j["frame"]["lateral"], r.frame_L.lateral_J, kJsonMm, "lateral");
  ExpectVec(j["frame"]["occlusal"], r.frame_L.occlusal_J, kJsonMm, "occlusal");
  ASSERT_EQ(j["teeth"]["upper"].size(), f.analysis.upper_U.teeth.size());
  for (std::size_t i = 0; i < f.analysis.upper_U.teeth.size(); ++i) {
    const analysis::ArchTooth& t = f.analysis.upper_U.teeth[i];
    EXPECT_EQ(j["teeth"]["upper"][i]["fdi"], t.fdi);
    EXPECT_EQ(j["teeth"]["upper"][i]["source"], analysis::ToString(t.source));
    ExpectVec(j["teeth"]["upper"][i]["centre"], f.pair.X_LU_ref * t.centre_J, kJsonMm, "centre");
  }
  const std::vector<analysis::ArchLandmark> landmarks =
      app::LandmarksInL(f.analysis, f.pair.X_LU_ref);
  ASSERT_EQ(j["landmarks"].size(), landmarks.size());
  int given = 0;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const json& l = j["landmarks"][i];
    EXPECT_EQ(l["jaw"], io::ToString(landmarks[i].landmark.jaw));
    EXPECT_EQ(l["tooth"], landmarks[i].landmark.tooth_fdi);
    EXPECT_EQ(l["type"], io::ToString(landmarks[i].landmark.type));
    EXPECT_EQ(l["source"], analysis::ToString(landmarks[i].source));
    EXPECT_DOUBLE_EQ(l["confidence"].get<double>(), landmarks[i].confidence);
    ExpectVec(l["p_L"], landmarks[i].landmark.p, kJsonMm, "p_L");
    given += l["source"] == "given";
  }
  EXPECT_EQ(given, 2);
  EXPECT_NEAR(j["relationships"]["overjet_mm"].get<double>(), *r.overjet.mm, kJsonMm);
  EXPECT_NEAR(j["relationships"]["molar_mm"]["right"].get<double>(), *r.molar[0].offset.mm,
              kJsonMm);
  EXPECT_EQ(j["relationships"]["crossbite"].size(), r.crossbite.size());
  EXPECT_TRUE(j["jaws"]["lower"]["error"].is_null());
  EXPECT_TRUE(j["warnings"].empty());
  EXPECT_TRUE(files.warnings.empty());
}

bool MarkerNear(const app::render::Image& img, const Eigen::Vector2d& px, app::render::Rgb c) {
  const int x0 = static_cast<int>(std::lround(px.x())), y0 = static_cast<int>(std::lround(px.y()));
  for (int y = y0 - kMarkerWindowPx; y <= y0 + kMarkerWindowPx; ++y) {
    for (int x = x0 - kMarkerWindowPx; x <= x0 + kMarkerWindowPx; ++x) {
      if (x >= 0 && y >= 0 && x < img.width && y < img.height && img.At(x, y) == c) return true;
    }
  }
  return false;
}

// Largest residual of the pixels of one jaw's landmarks fitted as an affine map of their points.
double ProjectionResidualPx(const std::vector<analysis::ArchLandmark>& landmarks,
                            const std::vector<Eigen::Vector2d>& px, io::Jaw jaw) {
  std::vector<int> rows;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    if (landmarks[i].landmark.jaw == jaw) rows.push_back(static_cast<int>(i));
  }
  Eigen::MatrixXd A(rows.size(), 4);
  Eigen::MatrixXd b(rows.size(), 2);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    A.row(k) << landmarks[rows[k]].landmark.p.transpose(), 1.0;
    b.row(k) = px[rows[k]].transpose();
  }
  const Eigen::MatrixXd fit = A.colPivHouseholderQr().solve(b);
  return (A * fit - b).rowwise().norm().maxCoeff();
}

TEST(AnalysisDocument, TheImageShowsAMarkerOfTheRightKindAtEveryLandmark) {
  const AnalysisFixture& f = SharedAnalysis();
  const std::vector<analysis::ArchLandmark> landmarks =
      app::LandmarksInL(f.analysis, f.pair.X_LU_ref);
  const analysis::Relationships r = app::RelationshipsAt(f.analysis, f.pair.X_LU_ref);
  const app::LandmarkImage img = app::RenderLandmarkMap(
      f.pair, f.pair.X_LU_ref, landmarks, app::ViewFrame(f.analysis, r, f.pair.X_LU_ref), 900);
  ASSERT_EQ(img.px.size(), landmarks.size());
  EXPECT_EQ(img.image.width, 900);
  int missing = 0;
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const bool given = landmarks[i].source == analysis::LandmarkSource::kGiven;
    const app::render::Rgb want = given ? app::kGivenLandmarkColour : app::kDetectedLandmarkColour;
    if (!MarkerNear(img.image, img.px[i], want)) {
      ++missing;
      ADD_FAILURE() << "no marker at " << io::ToString(landmarks[i].landmark.jaw) << " "
                    << landmarks[i].landmark.tooth_fdi << " "
                    << io::ToString(landmarks[i].landmark.type);
    }
  }
  EXPECT_EQ(missing, 0);
  EXPECT_LT(ProjectionResidualPx(landmarks, img.px, io::Jaw::kLower), kProjectionPx);
  EXPECT_LT(ProjectionResidualPx(landmarks, img.px, io::Jaw::kUpper), kProjectionPx);
}

}  // namespace
}  // namespace occlude::test
