// `occlude synth` through the real binary: it writes a case folder with the pose and the
// known contacts.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "run_occlude.h"
#include "test_common.h"

namespace occlude::test {
namespace {

TEST(CliTest, SynthWritesACaseFolder) {
  TempDir tmp;
  const CommandRun r = Occlude("synth --triangles 5000 --seed 2 --out " + (tmp / "case").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(tmp / "case" / "upper.stl"));
  EXPECT_TRUE(std::filesystem::exists(tmp / "case" / "lower.stl"));
  std::ifstream truth(tmp / "case" / "truth.json");
  std::stringstream text;
  text << truth.rdbuf();
  EXPECT_NE(text.str().find("\"X_LU\""), std::string::npos);
  EXPECT_NE(text.str().find("\"contacts\""), std::string::npos);
}

}  // namespace
}  // namespace occlude::test
