// `occlude validate` through the real binary: the files it writes, and bad options rejected
// with one line naming the option, writing nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "run_occlude.h"
#include "test_common.h"

namespace occlude::app {
namespace {

TEST(ValidateCommandTest, WritesItsFilesAndRejectsBadOptions) {
  test::TempDir tmp;
  const test::CommandRun ok = test::Occlude(
      "validate --synthetic 5000 --solver ceres --starts 1 --magnitudes 0.5:1 "
      "--voxels 0.5 --out " +
      (tmp / "v").string());
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  for (const char* f :
       {"validate.csv", "validate-summary.csv", "validate-summary.txt", "stability.png",
        "error.png", "time-vs-error.png", "reference-path.csv", "reference-path.png"}) {
    EXPECT_TRUE(std::filesystem::exists(tmp / "v" / f)) << f;
  }
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--synthetic 5000 --magnitudes 1-2", "--magnitudes"},
      {"--synthetic 5000 --solver simplex", "--solver"},
      {"--case " + (tmp / "missing").string(), "missing"},
      {"--synthetic 5000 --voxels 0", "--voxels"},
      {"--synthetic 100", "triangles"}};
  for (const auto& [args, expected] : bad) {
    const test::CommandRun r =
        test::Occlude("validate " + args + " --out " + (tmp / "bad").string());
    EXPECT_NE(r.exit_code, 0) << args;
    // One line of error (CLI11 adds a "Run with --help" hint for option errors).
    EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << args << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(tmp / "bad" / "validate.csv")) << args;
  }
}

}  // namespace
}  // namespace occlude::app
