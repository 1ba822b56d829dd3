// `occlude demo` through the real binary.
#include <gtest/gtest.h>

#include <string>

#include "case_run.h"
#include "config/pose_file.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::app {
namespace {

// `occlude demo` (what scripts/demo runs): propose on the embedded synthetic case finds the
// designed bite, writes the report and the case config it ran, which `refine` then takes.
TEST(DemoCommandTest, ProposesTheDesignedBiteAndLeavesARefinableCase) {
  test::TempDir tmp;
  const test::CommandRun r =
      test::Occlude("demo --triangles 5000 --voxel 0.5 --out " + (tmp / "demo").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f :
       {"report.html", "metrics.json", "pose.json", "proposals.json", "case.toml"}) {
    EXPECT_TRUE(std::filesystem::exists(tmp / "demo" / f)) << f;
  }
  const Eigen::Isometry3d best = ReadPoseFile(tmp / "demo" / "pose.json");
  EXPECT_LT(TranslationNorm(best), kFoundMm) << best.matrix();
  EXPECT_NE(r.output.find("of the designed bite"), std::string::npos) << r.output;
  const test::CommandRun refine = test::Occlude("refine " + (tmp / "demo" / "case.toml").string());
  ASSERT_EQ(refine.exit_code, 0) << refine.output;
  EXPECT_TRUE(std::filesystem::exists(tmp / "demo" / "refine.json"));
}

}  // namespace
}  // namespace occlude::app
