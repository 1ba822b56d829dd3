// `occlude collide` through the real binary on a generated case: it reports the bite's
// triangle pairs and writes collide.json.
#include <gtest/gtest.h>

#include <string>

#include "run_occlude.h"
#include "test_common.h"

namespace occlude::test {
namespace {

TEST(CliTest, CollideOnTheSyntheticCaseFindsTheBite) {
  TempDir tmp;
  ASSERT_EQ(Occlude("synth --triangles 5000 --out " + (tmp / "case").string()).exit_code, 0);
  const CommandRun r = Occlude("collide --lower " + (tmp / "case" / "lower.stl").string() +
                               " --upper " + (tmp / "case" / "upper.stl").string() +
                               " --voxel 0.3 --out " + (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("triangle pairs within the band"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(tmp / "out" / "collide.json"));
}

}  // namespace
}  // namespace occlude::test
