// `occlude report` through the real binary: it writes every file, and bad inputs give one
// line, a non-zero exit and no files.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "bench_files.h"
#include "config/pose_file.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::test {
namespace {

const std::string kSyntheticConfig =
    "[synthetic]\ntriangles = 5000\nseed = 1\n[report]\nimage_width_px = 900\n";

TEST(ReportCommand, WritesEveryFile) {
  TempDir tmp;
  std::ofstream(tmp / "case.toml") << kSyntheticConfig << "[output]\nfolder = \"report\"\n";
  std::ofstream(tmp / "pushed.json") << R"({"X_LU": [[1,0,0,0],[0,1,0,-0.2],[0,0,1,0],[0,0,0,1]]})";
  const CommandRun r = Occlude("report " + (tmp / "case.toml").string() + " --pose " +
                               (tmp / "pushed.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* name :
       {"report.html", "metrics.json", "pose.json", "upper_at_pose.stl", "upper_at_pose.ply",
        "lower.ply", "lower_map.png", "upper_map.png", "frontal.png", "lateral.png"}) {
    EXPECT_TRUE(std::filesystem::is_regular_file(tmp / "report" / name)) << name;
  }
  const std::string metrics = ReadFileText(tmp / "report" / "metrics.json");
  EXPECT_NE(metrics.find("\"within_allowed\": false"), std::string::npos);
  EXPECT_NE(metrics.find("\"relationships\": {"), std::string::npos);
  EXPECT_NE(metrics.find("\"overjet_mm\": "), std::string::npos);
  EXPECT_NE(ReadFileText(tmp / "report" / "report.html").find("<h2>Clinical relationships</h2>"),
            std::string::npos);
  EXPECT_NE(ReadFileText(tmp / "report" / "report.html").find("data:image/png;base64,"),
            std::string::npos);
  const Eigen::Isometry3d X = app::ReadPoseFile(tmp / "report" / "pose.json");
  EXPECT_NEAR(X.translation().y(), -0.2, 1e-12);
}

struct BadRun {
  const char* name;
  std::string config;  // written to {T}/case.toml ("" = no file)
  std::string extra;   // more arguments ({T} = temporary folder)
  const char* expected;
};

class ReportBadInputTest : public ::testing::TestWithParam<BadRun> {};

TEST_P(ReportBadInputTest, OneLineNonZeroExitNoFiles) {
  TempDir tmp;
  if (!GetParam().config.empty()) std::ofstream(tmp / "case.toml") << GetParam().config;
  std::ofstream(tmp / "scaled.json") << R"({"X_LU": [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})";
  const CommandRun r = Occlude(WithFolder("report " + (tmp / "case.toml").string() + " --out " +
                                              (tmp / "out").string() + " " + GetParam().extra,
                                          tmp.path()));
  ExpectOneErrorLine(r, GetParam().expected);
  std::error_code ec;
  EXPECT_TRUE(!std::filesystem::exists(tmp / "out", ec) ||
              std::filesystem::is_empty(tmp / "out", ec));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ReportBadInputTest,
    ::testing::Values(
        BadRun{"missing_config", "", "", "no such config file"},
        BadRun{"unknown_key", kSyntheticConfig + "[contact]\nbnd_mm = 0.1\n", "",
               "did you mean 'contact.band_mm'"},
        BadRun{"missing_mesh", "[lower]\nfile = \"nope.stl\"\n[upper]\nfile = \"nope.stl\"\n", "",
               "lower.file: no such file"},
        BadRun{"band_over_5mm", kSyntheticConfig + "[contact]\nband_mm = 7\n", "",
               "contact.band_mm"},
        BadRun{"non_rigid_pose_file", kSyntheticConfig, "--pose {T}/scaled.json",
               "not orthonormal"},
        BadRun{"missing_pose_file", kSyntheticConfig, "--pose {T}/nope.json", "nope.json"}),
    [](const ::testing::TestParamInfo<BadRun>& param_info) {
      return std::string(param_info.param.name);
    });

}  // namespace
}  // namespace occlude::test
