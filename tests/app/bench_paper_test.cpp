// `occlude bench --paper`: one row per voxel size (Figs. 4-8) and per voxel size
// and level (Fig. 9) with the documented columns and the relations that hold
// by construction (leaves = surface voxels, nodes at least the paper's own
// estimate, optimized spheres never larger than simple ones, one root), the
// query-rate sweep (Fig. 10, on the small sphere-on-box case) with every sphere
// mode, PNG charts; --mesh and --no-sweep have no Fig. 10; the fits are exact
// on exact data.
#include "bench/bench_paper.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "bench_files.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::test {
namespace {

TEST(PaperCommandTest, WritesTheBuildFiguresOnASyntheticJaw) {
  TempDir tmp;
  const CommandRun r = Occlude("bench --paper --synthetic 5000 --voxel 10,5,2 --no-sweep --out " +
                               (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto builds = ReadCsvRows(tmp / "out" / "paper-build.csv");
  ASSERT_EQ(builds.size(), 3u);
  std::set<std::string> voxels;
  for (const CsvRow& b : builds) {
    voxels.insert(b.at("voxel_mm"));
    EXPECT_EQ(b.at("surface_voxels"), b.at("leaves"));
    EXPECT_GE(Value(b, "nodes"), Value(b, "paper_min_nodes"));
    EXPECT_GE(Value(b, "paper_min_nodes"), Value(b, "leaves"));
    EXPECT_GT(Value(b, "voxelize_us"), 0.0);
    // The paper's dense grid holds every one of our surface voxels' cells and more.
    EXPECT_GT(Value(b, "paper_dense_cells"), Value(b, "surface_voxels"));
  }
  EXPECT_EQ(voxels, (std::set<std::string>{"10.000", "5.000", "2.000"}));

  std::map<std::string, int> levels_per_voxel, roots;
  for (const CsvRow& l : ReadCsvRows(tmp / "out" / "paper-levels.csv")) {
    ++levels_per_voxel[l.at("voxel_mm")];
    EXPECT_LE(Value(l, "optimized_mm3"), Value(l, "simple_mm3") * (1 + 1e-12));
    // In its unit (one simple sphere of the level), the simple volume is the node count.
    EXPECT_NEAR(Value(l, "simple_units"), Value(l, "nodes"), 1e-3 * Value(l, "nodes"));
    if (l.at("nodes") == "1") ++roots[l.at("voxel_mm")];
  }
  for (const CsvRow& b : builds) {
    EXPECT_EQ(levels_per_voxel[b.at("voxel_mm")], std::stoi(b.at("levels")));
    EXPECT_GE(roots[b.at("voxel_mm")], 1);  // the top level is one root
  }

  for (const char* chart :
       {"fig4-surface-voxels.png", "fig5-voxelize-time.png", "fig7-octree-time.png",
        "fig8-octree-nodes.png", "fig9-sphere-volume.png"}) {
    EXPECT_GT(PngFileSize(tmp / "out" / chart).first, 800) << chart;
  }
  EXPECT_FALSE(std::filesystem::exists(tmp / "out" / "paper-fig10.csv"));  // --no-sweep
  const auto fits = ReadCsvRows(tmp / "out" / "paper-fits.csv");
  EXPECT_GE(fits.size(), 5u);
  EXPECT_NE(ReadFileText(tmp / "out" / "paper-summary.txt").find("cores"), std::string::npos);
}

TEST(PaperCommandTest, WritesTheQueryRateFigureForEverySphereMode) {
  TempDir tmp;
  WriteSphereOnBoxCase(tmp / "case");
  const CommandRun r =
      Occlude("bench --paper --case " + (tmp / "case").string() +
              " --voxel 1 --sweep-voxel 0.8 --offsets 5,0 --reps 2 --no-fcl --out " +
              (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::set<std::string> sweep;
  for (const CsvRow& s : ReadCsvRows(tmp / "out" / "paper-fig10.csv")) {
    if (s.at("method") == "ist" && (s.at("query") == "boolean" || s.at("query") == "pairs")) {
      sweep.insert(s.at("variant") + "," + s.at("query") + "," + s.at("offset_mm"));
    }
  }
  for (const char* variant : {"simple", "optimized", "explicit"})
    for (const char* query : {"boolean", "pairs"})
      for (const char* offset : {"5.000", "0.000"})
        EXPECT_TRUE(sweep.count(std::string(variant) + "," + query + "," + offset))
            << variant << " " << query << " " << offset;

  for (const char* chart : {"fig10-boolean.png", "fig10-pairs.png"}) {
    EXPECT_GT(PngFileSize(tmp / "out" / chart).first, 800) << chart;
  }
}

TEST(PaperCommandTest, OneMeshFileHasNoQueryRateFigure) {
  TempDir tmp;
  WriteSphereOnBoxCase(tmp / "case");
  const CommandRun r = Occlude("bench --paper --mesh " + (tmp / "case" / "upper.stl").string() +
                               " --voxel 2,0.5 --out " + (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(ReadCsvRows(tmp / "out" / "paper-build.csv").size(), 2u);
  EXPECT_TRUE(std::filesystem::exists(tmp / "out" / "fig4-surface-voxels.png"));
  EXPECT_FALSE(std::filesystem::exists(tmp / "out" / "fig10-boolean.png"));
  EXPECT_FALSE(std::filesystem::exists(tmp / "out" / "paper-fig10.csv"));
}

TEST(PaperCommandTest, MissingMeshNamesTheFileAndWritesNothing) {
  TempDir tmp;
  const CommandRun r = Occlude("bench --paper --mesh " + (tmp / "nothere.stl").string() +
                               " --out " + (tmp / "out").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("nothere.stl"), std::string::npos) << r.output;
  EXPECT_TRUE(EmptyOrMissing(tmp / "out"));
}

TEST(PowerFitTest, RecoversTheExponentOfAPowerLaw) {
  const std::vector<double> s = {0.1, 0.2, 0.4, 0.8, 1.0};
  std::vector<double> y;
  for (const double v : s) y.push_back(3.0 * std::pow(v, -2.0));
  const app::PowerFit fit = app::FitPowerLaw(s, y, "test");
  EXPECT_NEAR(fit.exponent, -2.0, 1e-12);
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
  EXPECT_EQ(fit.points, 5u);
  // Non-positive values are left out, not fitted.
  const app::PowerFit partial = app::FitPowerLaw({1.0, 2.0, 0.0}, {1.0, 8.0, 5.0}, "cube");
  EXPECT_NEAR(partial.exponent, 3.0, 1e-12);
  EXPECT_EQ(partial.points, 2u);
}

TEST(AffineFitTest, RecoversInterceptAndSlopeOfALine) {
  const app::AffineFit fit = app::FitAffine({1, 2, 4, 8}, {5, 7, 11, 19}, "line");
  EXPECT_NEAR(fit.intercept, 3.0, 1e-12);
  EXPECT_NEAR(fit.slope, 2.0, 1e-12);
  EXPECT_NEAR(fit.r2, 1.0, 1e-12);
}

}  // namespace
}  // namespace occlude::test
