// The global scope through the real binary, on the small synthetic pair with a coarse scan:
// `propose --global` from a start 7 mm forward along the arch finds the designed bite first
// and labels it; jaws without teeth are one clear error; `validate --global` writes the start
// kinds and the seat columns (one start per kind), and from cusp starts ranks by a --clinical
// file; its global-only options are checked first.
#include <gtest/gtest.h>

#include <algorithm>
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

// The column of a CSV header, -1 when absent.
int ColumnOf(const std::string& header, const std::string& name) {
  std::istringstream s(header);
  std::string cell;
  for (int i = 0; std::getline(s, cell, ','); ++i) {
    if (cell == name) return i;
  }
  return -1;
}

std::string Cell(const std::string& line, int column) {
  std::istringstream s(line);
  std::string cell;
  for (int i = 0; i <= column; ++i) std::getline(s, cell, ',');
  return cell;
}

// --kinds cusp: starts a cusp period (7 mm, the pair's Class II shift) forward and back, ranked
// by --clinical's molar Class I: the designed (Class I) bite first, the targets met, the
// targets named in the summary.
TEST(GlobalCommandTest, ValidateGlobalFromCuspStartsRanksByTheClinicalFile) {
  test::TempDir tmp;
  std::ofstream(tmp / "targets.toml") << "[clinical]\nmolar_class = \"I\"\n";
  const test::CommandRun r = test::Occlude(
      "validate --global --synthetic 5000 --starts 2 --threads 1 --voxels 1.2 --scan-step 5 "
      "--basins 2,1 --kinds cusp --clinical " +
      (tmp / "targets.toml").string() + " --out " + (tmp / "v").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::istringstream csv(Read(tmp / "v" / "validate.csv"));
  std::string header, line;
  std::getline(csv, header);
  const int kind = ColumnOf(header, "start_kind"), start_err = ColumnOf(header, "start_err_mm"),
            molar = ColumnOf(header, "top_molar_class"), met = ColumnOf(header, "targets_met"),
            seat = ColumnOf(header, "seat_success");
  ASSERT_GE(std::min({kind, start_err, molar, met, seat}), 0) << header;
  int rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    EXPECT_EQ(Cell(line, kind), "cusp") << line;
    // 7 mm along the arch, up to 0.5 mm and 3 deg more: the reference points move 6.5-10 mm.
    EXPECT_GT(std::stod(Cell(line, start_err)), 6.4) << line;
    EXPECT_LT(std::stod(Cell(line, start_err)), 10.5) << line;
    EXPECT_EQ(Cell(line, molar), "I/I") << line;
    EXPECT_EQ(Cell(line, met), "1") << line;
    EXPECT_EQ(Cell(line, seat), "1") << line;
  }
  EXPECT_EQ(rows, 2);
  const std::string summary = Read(tmp / "v" / "validate-summary.txt");
  EXPECT_NE(summary.find("clinical targets (--clinical): molar I/I, canine -/-; rank"),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("cusp starts 7.0 mm off"), std::string::npos) << summary;
}

// The global-only options without --global, an unknown kind and a missing targets file: one
// line each, nothing written.
TEST(GlobalCommandTest, ValidateGlobalOptionsAreCheckedBeforeAnyWork) {
  test::TempDir tmp;
  const struct {
    std::string args;
    const char* says;
  } cases[] = {
      {"--kinds cusp", "--kinds applies to --global only"},
      {"--clinical x.toml", "--clinical applies to --global only"},
      {"--global --kinds sideways", "sideways"},
      {"--global --clinical " + (tmp / "none.toml").string(), "none.toml: no such config file"},
  };
  for (const auto& c : cases) {
    const test::CommandRun r =
        test::Occlude("validate --synthetic 5000 " + c.args + " --out " + (tmp / "v").string());
    EXPECT_NE(r.exit_code, 0) << c.args;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << " -> " << r.output;
    EXPECT_FALSE(std::filesystem::exists(tmp / "v")) << c.args;
  }
}

}  // namespace
}  // namespace occlude::app
