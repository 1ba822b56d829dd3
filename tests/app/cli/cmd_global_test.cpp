// The global scope through the real binary, on the small synthetic pair with a coarse scan:
// `propose --global` from a start 7 mm forward along the arch finds the designed bite first
// and labels it; jaws without teeth are one clear error; `validate --global` writes the start
// kinds and the seat columns (one start per kind).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "occlude/io/mesh_io.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::app {
namespace {

// The designed bite is X_LU = I in the session's frame; the bar of validate's success.
constexpr double kSeatMm = 0.3;
constexpr double kStartShiftMm = 7.0;  // along +z, the synthetic pair's anterior axis

const char* const kCoarseGlobal =
    "[synthetic]\ntriangles = 6000\n[accuracy]\nvoxel_mm = 0.8\nsample_spacing_mm = 0.6\n"
    "[solver]\nthreads = 1\nproposals = 2\n[solver.global]\nsagittal_step_mm = 2\n"
    "max_basins = 4\nmax_refined = 2\n";

std::string Read(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(GlobalCommandTest, ProposeGlobalFindsTheDesignedBiteFromASagittalStart) {
  test::TempDir tmp;
  std::ofstream(tmp / "case.toml")
      << kCoarseGlobal << "[start]\ntranslation_mm = [0, 0, " << kStartShiftMm << "]\n";
  const test::CommandRun r = test::Occlude("propose --global " + (tmp / "case.toml").string() +
                                           " --out " + (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(Read(tmp / "out" / "proposals.json"));
  EXPECT_EQ(j["scope"], "global");
  ASSERT_FALSE(j["proposals"].empty());
  const nlohmann::json& best = j["proposals"][0];
  const Eigen::Vector3d t(best["X_LU"][0][3], best["X_LU"][1][3], best["X_LU"][2][3]);
  EXPECT_LT(t.norm(), kSeatMm) << best.dump();
  const nlohmann::json& label = best["global"];
  EXPECT_EQ(label["rank"], 1);
  EXPECT_NEAR(label["from_given"]["sagittal_mm"].get<double>(), -kStartShiftMm, 2 * kSeatMm);
  // The one schema of the relationships (as in analysis.json and metrics.json).
  EXPECT_EQ(label["relationships"]["molar_class"]["right"], "I");
  EXPECT_EQ(label["relationships"]["molar_class"]["left"], "I");
  EXPECT_TRUE(label["relationships"].contains("overjet_mm"));
  EXPECT_TRUE(label.contains("targets"));
  EXPECT_NE(Read(tmp / "out" / "report.html").find("Global search"), std::string::npos);
}

TEST(GlobalCommandTest, JawsWithoutTeethAreOneClearError) {
  test::TempDir tmp;
  io::WriteBinaryStl(test::MakeBox({0, 0, 0}, {40, 10, 30}), tmp / "lower.stl");
  io::WriteBinaryStl(test::MakeBox({0, 11, 0}, {40, 21, 30}), tmp / "upper.stl");
  std::ofstream(tmp / "case.toml")
      << "[lower]\nfile = \"lower.stl\"\n[upper]\nfile = \"upper.stl\"\n[solver]\n"
         "scope = \"global\"\n";
  const test::CommandRun r =
      test::Occlude("propose " + (tmp / "case.toml").string() + " --out " + (tmp / "out").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("case.toml: the lower jaw"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(tmp / "out" / "proposals.json"));
}

TEST(GlobalCommandTest, ValidateGlobalWritesTheStartKindsAndSeatColumns) {
  test::TempDir tmp;
  const test::CommandRun r = test::Occlude(
      "validate --global --synthetic 5000 --starts 1 --threads 1 --voxels 1.2 --scan-step 5 "
      "--basins 2,1 --out " +
      (tmp / "v").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f :
       {"validate.csv", "validate-summary.csv", "validate-summary.txt", "stability.png"}) {
    EXPECT_TRUE(std::filesystem::exists(tmp / "v" / f)) << f;
  }
  std::istringstream csv(Read(tmp / "v" / "validate.csv"));
  std::string header, line;
  std::getline(csv, header);
  for (const char* column :
       {"start_kind", "seat_success", "seat_err_mm", "seat_err_deg", "seat_rank", "success"}) {
    EXPECT_NE(header.find(column), std::string::npos) << column;
  }
  std::string kinds;
  while (std::getline(csv, line)) kinds += line.substr(0, line.find(',')) + " ";
  EXPECT_EQ(kinds, "near sagittal apart ");
}

}  // namespace
}  // namespace occlude::app
