// `occlude analyze` through the real binary on the synthetic pair (5,000 triangles per jaw):
// analysis.json against the library's answer (a case session of the same config, in this
// process) field by field; landmarks.png by its pixels (a marker of the detected or given colour
// at every landmark's pixel); given landmarks from the case folder, the config key and
// --landmarks (which overrides the key); the upper landmarks moving with --pose; a jaw without
// teeth is a warning and the rest is written; bad inputs are one line, a non-zero exit and no
// analysis.json.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "config/case_config.h"
#include "occlude/angles.h"
#include "occlude/io/landmark_file.h"
#include "occlude/io/mesh_io.h"
#include "occlude/io/synthetic_jaws.h"
#include "run_occlude.h"
#include "session/case_analysis.h"
#include "session/case_session.h"
#include "test_common.h"

namespace occlude::test {
namespace {

using nlohmann::json;

const std::string kConfig =
    "[synthetic]\ntriangles = 5000\nseed = 1\n[report]\nimage_width_px = 400\n";
constexpr double kJsonMm = 1e-9;
// Marker colours of report/report_images.h (RGB): detected, given.
constexpr int kDetected[3] = {0, 102, 204};
constexpr int kGiven[3] = {230, 110, 0};

json ReadJson(const std::filesystem::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

// A few of the synthetic pair's designed landmarks, in the frames of a case folder from
// `occlude synth` (upper ones in L at the bite), as a landmark file.
std::string DesignedRows(int count) {
  const io::SyntheticJawPair design = io::MakeSyntheticJawPair({5000, 1});
  std::vector<io::Landmark> l = app::GivenAtReference(design.X_LU, design.landmarks);
  l.resize(static_cast<std::size_t>(count));
  return io::FormatLandmarkFile(l);
}

// The unit mesio-distal direction of lower tooth `fdi` in analysis.json (its mesial minus its
// distal landmark, p_L) in the plane of the relationships' frame.
Eigen::Vector3d MesioDistal(const json& analysis, int fdi) {
  Eigen::Vector3d mesial = Eigen::Vector3d::Zero(), distal = Eigen::Vector3d::Zero();
  for (const json& l : analysis["landmarks"]) {
    if (l["jaw"] != "lower" || l["tooth"] != fdi) continue;
    const Eigen::Vector3d p(l["p_L"][0].get<double>(), l["p_L"][1].get<double>(),
                            l["p_L"][2].get<double>());
    if (l["type"] == "mesial") mesial = p;
    if (l["type"] == "distal") distal = p;
  }
  const json& z = analysis["frame"]["occlusal"];
  const Eigen::Vector3d up(z[0].get<double>(), z[1].get<double>(), z[2].get<double>());
  const Eigen::Vector3d t = mesial - distal;
  return (t - t.dot(up) * up).normalized();
}

int GivenCount(const json& analysis) {
  return static_cast<int>(std::count_if(analysis["landmarks"].begin(), analysis["landmarks"].end(),
                                        [](const json& l) { return l["source"] == "given"; }));
}

TEST(AnalyzeCommand, AnalysisJsonIsTheLibrarysAnswerFieldByField) {
  TempDir tmp;
  std::ofstream(tmp / "case.toml") << kConfig;
  const CommandRun r =
      Occlude("analyze " + (tmp / "case.toml").string() + " --out " + (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("analysis in"), std::string::npos) << r.output;
  const json j = ReadJson(tmp / "out" / "analysis.json");
  app::CaseSession session(app::LoadCaseConfig(tmp / "case.toml"));
  const app::CaseAnalysis& a = session.Analysis();
  const Eigen::Isometry3d X_LU = session.ConfigStartPose();
  const analysis::Relationships rel = app::RelationshipsAt(a, X_LU);
  const std::vector<analysis::ArchLandmark> landmarks = app::LandmarksInL(a, X_LU);
  ASSERT_EQ(j["landmarks"].size(), landmarks.size());
  for (std::size_t i = 0; i < landmarks.size(); ++i) {
    const json& l = j["landmarks"][i];
    EXPECT_EQ(l["tooth"], landmarks[i].landmark.tooth_fdi);
    EXPECT_EQ(l["type"], io::ToString(landmarks[i].landmark.type));
    EXPECT_EQ(l["source"], "detected");
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(l["p_L"][k].get<double>(), landmarks[i].landmark.p[k], kJsonMm);
  }
  ASSERT_EQ(j["teeth"]["lower"].size(), a.lower_L.teeth.size());
  for (std::size_t i = 0; i < a.lower_L.teeth.size(); ++i) {
    EXPECT_EQ(j["teeth"]["lower"][i]["fdi"], a.lower_L.teeth[i].fdi);
  }
  const json& rj = j["relationships"];
  const auto expect = [&](const json& value, const analysis::Measure& m, const char* what) {
    if (m.mm) {
      EXPECT_NEAR(value.get<double>(), *m.mm, kJsonMm) << what;
    } else {
      EXPECT_TRUE(value.is_null()) << what;
    }
  };
  expect(rj["overjet_mm"], rel.overjet, "overjet");
  expect(rj["overbite_mm"], rel.overbite, "overbite");
  expect(rj["midline_deviation_mm"], rel.midline_deviation, "midline");
  expect(rj["molar_mm"]["right"], rel.molar[0].offset, "molar right");
  expect(rj["molar_mm"]["left"], rel.molar[1].offset, "molar left");
  expect(rj["canine_mm"]["right"], rel.canine[0].offset, "canine right");
  expect(rj["canine_mm"]["left"], rel.canine[1].offset, "canine left");
  EXPECT_EQ(rj["crossbite"].get<std::vector<int>>(), rel.crossbite);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(j["frame"]["anterior"][k].get<double>(), rel.frame_L.anterior_J[k], kJsonMm);
  }
}

bool PixelNear(const cv::Mat& bgr, const json& px, const int (&rgb)[3]) {
  const int x0 = static_cast<int>(std::lround(px[0].get<double>()));
  const int y0 = static_cast<int>(std::lround(px[1].get<double>()));
  for (int y = y0 - 1; y <= y0 + 1; ++y) {
    for (int x = x0 - 1; x <= x0 + 1; ++x) {
      if (x < 0 || y < 0 || x >= bgr.cols || y >= bgr.rows) continue;
      const cv::Vec3b c = bgr.at<cv::Vec3b>(y, x);
      if (c[2] == rgb[0] && c[1] == rgb[1] && c[0] == rgb[2]) return true;
    }
  }
  return false;
}

TEST(AnalyzeCommand, CaseFolderLandmarksAreGivenDrawnAsSuchAndMoveWithThePose) {
  TempDir tmp;
  ASSERT_EQ(Occlude("synth --triangles 5000 --out " + (tmp / "case").string()).exit_code, 0);
  std::ofstream(tmp / "case" / "landmarks.csv") << DesignedRows(6);
  std::ofstream(tmp / "moved.json") << R"({"X_LU": [[1,0,0,0],[0,1,0,0.5],[0,0,1,2],[0,0,0,1]]})";
  const std::string run = "analyze --case " + (tmp / "case").string() + " --out ";
  const CommandRun r = Occlude(run + (tmp / "bite").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json bite = ReadJson(tmp / "bite" / "analysis.json");
  EXPECT_EQ(GivenCount(bite), 6);
  const cv::Mat png = cv::imread((tmp / "bite" / "landmarks.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(png.empty());
  int missing = 0;
  for (const json& l : bite["landmarks"]) {
    if (!PixelNear(png, l["png_px"], l["source"] == "given" ? kGiven : kDetected)) ++missing;
  }
  EXPECT_EQ(missing, 0);
  // At a pose 0.5 mm up and 2 mm forward the upper landmarks move by it, the lower ones stay.
  ASSERT_EQ(Occlude(run + (tmp / "moved").string() + " --pose " + (tmp / "moved.json").string())
                .exit_code,
            0);
  const json moved = ReadJson(tmp / "moved" / "analysis.json");
  ASSERT_EQ(bite["landmarks"].size(), moved["landmarks"].size());
  for (std::size_t i = 0; i < bite["landmarks"].size(); ++i) {
    const json &a = bite["landmarks"][i], &b = moved["landmarks"][i];
    const bool upper = a["jaw"] == "upper";
    EXPECT_NEAR(b["p_L"][1].get<double>() - a["p_L"][1].get<double>(), upper ? 0.5 : 0.0, kJsonMm);
    EXPECT_NEAR(b["p_L"][2].get<double>() - a["p_L"][2].get<double>(), upper ? 2.0 : 0.0, kJsonMm);
  }
  // The molar offset is measured along the lower 46's mesio-distal direction t (its mesial minus
  // its distal landmark, in the occlusal plane): the move (0, 0.5, 2) mm adds its component
  // along t (2 mm when t is the anterior axis +z; the detected t of this coarse segmented pair
  // may turn from it by 10-20 deg).
  const Eigen::Vector3d t = MesioDistal(bite, 46);
  EXPECT_GT(t.z(), std::cos(RadiansFromDegrees(30.0))) << t.transpose();
  EXPECT_NEAR(moved["relationships"]["molar_mm"]["right"].get<double>() -
                  bite["relationships"]["molar_mm"]["right"].get<double>(),
              Eigen::Vector3d(0.0, 0.5, 2.0).dot(t), 0.05);
}

TEST(AnalyzeCommand, TheLandmarksOptionOverridesTheConfigKey) {
  TempDir tmp;
  std::ofstream(tmp / "key.csv") << DesignedRows(3);
  std::ofstream(tmp / "option.csv") << DesignedRows(5);
  std::ofstream(tmp / "case.toml") << kConfig << "[landmarks]\nfile = \"key.csv\"\n";
  const std::string config = "analyze " + (tmp / "case.toml").string() + " --out ";
  ASSERT_EQ(Occlude(config + (tmp / "a").string()).exit_code, 0);
  EXPECT_EQ(GivenCount(ReadJson(tmp / "a" / "analysis.json")), 3);
  ASSERT_EQ(Occlude(config + (tmp / "b").string() + " --landmarks " + (tmp / "option.csv").string())
                .exit_code,
            0);
  EXPECT_EQ(GivenCount(ReadJson(tmp / "b" / "analysis.json")), 5);
}

TEST(AnalyzeCommand, AJawWithoutTeethIsAWarningAndTheRestIsWritten) {
  TempDir tmp;
  std::filesystem::create_directories(tmp / "case");
  const io::SyntheticJawPair design = io::MakeSyntheticJawPair({5000, 1});
  io::WriteBinaryStl(design.lower_L, tmp / "case" / "lower.stl");
  io::WriteBinaryStl(MakeBox({-20, 5, -20}, {20, 15, 20}), tmp / "case" / "upper.stl");
  const CommandRun r =
      Occlude("analyze --case " + (tmp / "case").string() + " --out " + (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("occlude: warning: no tooth found on the upper jaw"), std::string::npos)
      << r.output;
  const json j = ReadJson(tmp / "out" / "analysis.json");
  EXPECT_FALSE(j["jaws"]["upper"]["error"].is_null());
  EXPECT_FALSE(j["teeth"]["lower"].empty());
  EXPECT_TRUE(j["relationships"]["overjet_mm"].is_null());
  EXPECT_TRUE(j["relationships"]["overjet_reason"].is_string());
  EXPECT_TRUE(std::filesystem::is_regular_file(tmp / "out" / "landmarks.png"));
}

struct AnalyzeBadRun {
  const char* name;
  std::string args;  // after "analyze " ({T} = the temporary folder)
  const char* expected;
};

class AnalyzeBadInputTest : public ::testing::TestWithParam<AnalyzeBadRun> {};

TEST_P(AnalyzeBadInputTest, OneLineNonZeroExitNoAnalysis) {
  TempDir tmp;
  std::ofstream(tmp / "case.toml") << kConfig;
  std::ofstream(tmp / "bad.csv") << "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,11,incisal_edge,0,0,0\n"
                                 << "lower,46,cusp,1,2,3\n";
  ExpectOneErrorLine(Occlude(WithFolder("analyze " + GetParam().args, tmp.path())),
                     GetParam().expected);
  EXPECT_FALSE(std::filesystem::exists(tmp / "out" / "analysis.json"));
}

INSTANTIATE_TEST_SUITE_P(
    Analyze, AnalyzeBadInputTest,
    ::testing::Values(
        AnalyzeBadRun{"bad_landmark_type", "{T}/case.toml --landmarks {T}/bad.csv --out {T}/out",
                      "bad.csv: line 3: type"},
        AnalyzeBadRun{"missing_landmark_file",
                      "{T}/case.toml --landmarks {T}/none.csv --out {T}/out",
                      "none.csv: no such file"},
        AnalyzeBadRun{"neither_config_nor_case", "--out {T}/out", "give either a case config"},
        AnalyzeBadRun{"both_config_and_case", "{T}/case.toml --case {T} --out {T}/out", "not both"},
        AnalyzeBadRun{"case_without_out", "--case {T}", "--out: give the output folder"}),
    [](const ::testing::TestParamInfo<AnalyzeBadRun>& param) {
      return std::string(param.param.name);
    });

}  // namespace
}  // namespace occlude::test
