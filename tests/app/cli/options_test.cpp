// The options as a user gives them to the real binary (OCCLUDE_BINARY, injected by CMake): a
// bad value (zero voxel, negative or over-5-mm band, unknown units, a triangle budget out of
// range) gives one line naming the option, a non-zero exit and no output file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "run_occlude.h"
#include "test_common.h"

namespace occlude::test {
namespace {

struct BadCase {
  const char* name;
  std::string args;      // {T} = temporary folder
  const char* expected;  // substring of the one-line message
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }  // not its bytes

class CliBadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(CliBadInputTest, OneLineErrorNonZeroExitAndNoOutput) {
  TempDir tmp;
  {
    std::ofstream(tmp / "garbage.stl") << "this is not a mesh\n";
    std::ofstream(tmp / "empty.stl");
    std::ofstream(tmp / "scaled.json") << R"({"X_LU": [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})";
    std::ofstream(tmp / "nan.json") << R"({"X_LU": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0]]})";
  }
  ASSERT_EQ(Occlude("synth --triangles 5000 --out " + (tmp / "case").string()).exit_code, 0);
  std::string args = GetParam().args;
  for (std::size_t at; (at = args.find("{T}")) != std::string::npos;)
    args.replace(at, 3, tmp.path().string());
  const CommandRun r = Occlude(args + " --out " + (tmp / "out").string());
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(GetParam().expected), std::string::npos) << r.output;
  EXPECT_TRUE(EmptyOrMissing(tmp / "out")) << "a failed run wrote output";
  // One line of error (CLI11 adds a "Run with --help" hint for option errors).
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 2) << r.output;
}

const std::string kGood = " --lower {T}/case/lower.stl --upper {T}/case/upper.stl";

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadInputTest,
    ::testing::Values(
        BadCase{"missing_file", "collide --lower {T}/nope.stl --upper {T}/case/upper.stl",
                "no such file"},
        BadCase{"garbage_file", "collide --lower {T}/garbage.stl --upper {T}/case/upper.stl",
                "garbage.stl"},
        BadCase{"empty_file", "collide --lower {T}/empty.stl --upper {T}/case/upper.stl",
                "empty.stl"},
        BadCase{"folder_as_mesh", "collide --lower {T}/case --upper {T}/case/upper.stl", "case"},
        BadCase{"zero_voxel", "collide" + kGood + " --voxel 0", "--voxel"},
        BadCase{"negative_band", "collide" + kGood + " --delta -1", "--delta"},
        BadCase{"band_over_5mm", "collide" + kGood + " --delta 6", "--delta"},
        BadCase{"bad_units", "collide" + kGood + " --units furlong", "--units"},
        BadCase{"scaled_pose", "collide" + kGood + " --pose {T}/scaled.json", "not orthonormal"},
        BadCase{"broken_pose", "collide" + kGood + " --pose {T}/nan.json", "nan.json"},
        BadCase{"tiny_voxel_overflows", "collide" + kGood + " --voxel 0.00001",
                "smallest voxel size"},
        BadCase{"synth_budget", "synth --triangles 100", "--triangles"}),
    [](const ::testing::TestParamInfo<BadCase>& param_info) {
      return std::string(param_info.param.name);
    });

}  // namespace
}  // namespace occlude::test
