// `occlude bench` through the real binary. The sweep: the CSV has the documented columns and
// one row per method, variant, voxel size, query kind and offset, the speedups are FCL's median
// over IST's, the charts are PNG files; the haptic loop reports every tick; bad inputs write
// nothing. --paper: one row per voxel size (Figs. 4-8) and per voxel size and level (Fig. 9)
// with the documented columns and the relations that hold by construction (leaves = surface
// voxels, nodes at least the paper's own estimate, optimized spheres never larger than simple
// ones, one root), the query-rate sweep (Fig. 10, on the small sphere-on-box case) with every
// sphere mode, PNG charts; --mesh and --no-sweep have no Fig. 10. --accuracy on the
// sphere-on-box case (one run shared by the tests): every documented column, one row per method
// / variant / voxel size / query / level, PNG charts, the planner's JSON table, and numbers that
// must hold by construction: the exact oracle level has zero error against the ground truth,
// the voxel level errs by at most half a voxel on the flat box and interpolation not at all,
// coarser voxels have larger errors, the voxel-pair query misses no contact near the surface
// (it is conservative) and the exact pair query invents none, and the three sphere modes answer
// alike.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "bench_files.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::test {
namespace {

// Whether the binary was built with the FCL peer (its rows are then expected).
constexpr bool kBuiltWithFcl = OCCLUDE_BUILT_WITH_FCL;
// Whether it was built with the OpenVDB peer.
constexpr bool kBuiltWithOpenVdb = OCCLUDE_BUILT_WITH_OPENVDB;

// --- the occlusal-axis sweep ----------------------------------------------------------------

TEST(BenchCommandTest, WritesOneRowPerMethodQueryAndOffsetWithTheDocumentedColumns) {
  TempDir tmp;
  const CommandRun r = Occlude(
      "bench --synthetic 5000 --voxel 0.8,0.4 --reps 1 --rounds 2 --offsets 1,0,-0.1 --out " +
      (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string header = ReadFileText(tmp / "out" / "bench.csv").substr(0, 200);
  EXPECT_EQ(header.rfind(
                "method,variant,voxel_mm,query,offset_mm,median_us,max_us,rate_hz,pairs,bytes", 0),
            0u)
      << header;
  const auto rows = ReadCsvRows(tmp / "out" / "bench.csv");
  std::set<std::string> keys;
  for (const auto& row : rows) {
    const std::string key = row.at("method") + "," + row.at("variant") + "," + row.at("voxel_mm") +
                            "," + row.at("query") + "," + row.at("offset_mm") + "," +
                            row.at("structure");
    EXPECT_TRUE(keys.insert(key).second) << "duplicate row " << key;
    if (row.at("query") == "build") {
      EXPECT_GT(std::stod(row.at("bytes")), 0.0) << key;
      EXPECT_GT(std::stod(row.at("median_us")), 0.0) << key;
    } else {
      EXPECT_GT(std::stod(row.at("rate_hz")), 0.0) << key;
      EXPECT_LE(std::stod(row.at("median_us")), std::stod(row.at("max_us"))) << key;
    }
  }
  for (const char* voxel : {"0.800", "0.400"}) {
    for (const char* variant : {"simple", "optimized", "explicit"}) {
      EXPECT_TRUE(keys.count(std::string("ist,") + variant + "," + voxel + ",build,,trees"))
          << variant;
      for (const char* query : {"boolean", "pairs"}) {
        for (const char* offset : {"1.000", "0.000", "-0.100"}) {
          EXPECT_TRUE(keys.count(std::string("ist,") + variant + "," + voxel + "," + query + "," +
                                 offset + ","))
              << variant << " " << query << " " << offset;
        }
      }
    }
    for (const char* query : {"oracle-voxel", "oracle-subvoxel", "oracle-exact"}) {
      EXPECT_TRUE(keys.count(std::string("ist,explicit,") + voxel + "," + query + ",0.000,"))
          << query;
    }
    // The oracle as the commands build it (without the pair queries' trees) beside the
    // bench's own: smaller by the trees' explicit spheres and the upper's bound.
    double commands_bytes = 0.0, bench_bytes = 0.0;
    for (const auto& row : rows) {
      if (row.at("method") != "ist" || row.at("query") != "build" || row.at("voxel_mm") != voxel)
        continue;
      if (row.at("structure") == "commands-oracle") commands_bytes = std::stod(row.at("bytes"));
      if (row.at("structure") == "oracle") bench_bytes = std::stod(row.at("bytes"));
    }
    EXPECT_GT(commands_bytes, 0.0) << voxel;
    EXPECT_LT(commands_bytes, bench_bytes) << voxel;
  }
  // At the bite pairs exist, fewer 1 mm open; pushed 0.1 mm in, the exact
  // penetration (normal depth, not along the axis) is positive and at most 0.1 mm.
  std::map<std::string, int> pairs_at;
  for (const auto& row : rows) {
    if (row.at("method") != "ist" || row.at("voxel_mm") != "0.400") continue;
    if (row.at("query") == "pairs" && row.at("variant") == "explicit") {
      pairs_at[row.at("offset_mm")] = std::stoi(row.at("pairs"));
    }
    if (row.at("query") == "oracle-exact" && row.at("offset_mm") == "-0.100") {
      EXPECT_GT(std::stod(row.at("max_penetration_mm")), 0.02);
      EXPECT_LE(std::stod(row.at("max_penetration_mm")), 0.1 + 1e-3);
    }
    if (row.at("query") == "oracle-exact" && row.at("offset_mm") == "1.000") {
      EXPECT_EQ(std::stod(row.at("max_penetration_mm")), 0.0);
    }
  }
  EXPECT_GT(pairs_at["0.000"], pairs_at["1.000"]);
  EXPECT_GE(pairs_at["-0.100"], pairs_at["0.000"]);
  if (kBuiltWithFcl) {
    EXPECT_TRUE(keys.count("fcl,obb,,boolean,0.000,"));
    EXPECT_TRUE(keys.count("fcl,obbrss,,collide-all,0.000,"));
    EXPECT_TRUE(keys.count("fcl,obbrss,,distance,1.000,"));
    EXPECT_TRUE(keys.count("fcl,obbrss,,build,,trees"));
    // Speedups from the rows' (merged over the rounds) medians: FCL / IST at the offset.
    std::map<std::string, double> fcl_us;  // "obb:boolean@0.000" -> median
    for (const auto& row : rows) {
      if (row.at("method") == "fcl" && row.at("query") != "build") {
        fcl_us[row.at("variant") + ":" + row.at("query") + "@" + row.at("offset_mm")] =
            std::stod(row.at("median_us"));
      }
    }
    for (const auto& row : rows) {
      if (row.at("method") == "ist" && row.at("query") == "boolean") {
        EXPECT_EQ(row.at("fcl_reference"), "obb:boolean");
        EXPECT_FALSE(row.at("speedup_vs_fcl").empty());
      }
      if (row.at("method") == "ist" && !row.at("fcl_reference").empty()) {
        const double ratio = fcl_us.at(row.at("fcl_reference") + "@" + row.at("offset_mm")) /
                             std::stod(row.at("median_us"));
        // Printed with 2 decimals (the medians too): equal within that rounding.
        EXPECT_NEAR(std::stod(row.at("speedup_vs_fcl")), ratio, 0.006 + 0.01 * ratio)
            << row.at("query");
      }
      if (row.at("method") == "fcl" && row.at("query") == "boolean") {
        EXPECT_EQ(row.at("pairs"), row.at("offset_mm") == "1.000" ? "0" : "1")
            << row.at("offset_mm");
      }
      if (row.at("method") == "fcl" && row.at("query") == "distance" &&
          row.at("offset_mm") == "1.000") {
        EXPECT_GT(std::stod(row.at("min_distance_mm")), 0.5);
      }
    }
  }
  for (const char* chart :
       {"boolean-0.80mm.png", "pairs-0.40mm.png", "oracle-0.40mm.png", "boolean-by-voxel.png"}) {
    const auto size = PngFileSize(tmp / "out" / chart);
    EXPECT_GT(size.first, 400) << chart;
    EXPECT_GT(size.second, 300) << chart;
  }
  EXPECT_NE(ReadFileText(tmp / "out" / "bench-summary.txt").find("cores"), std::string::npos);
  // OpenVDB's rows are there by default when the binary has it (their content: the next test).
  EXPECT_EQ(keys.count("openvdb,levelset,0.800,build,,grid"), kBuiltWithOpenVdb ? 1u : 0u);
  EXPECT_EQ(keys.count("openvdb,levelset,0.400,oracle-subvoxel,0.000,"),
            kBuiltWithOpenVdb ? 1u : 0u);
}

// The OpenVDB peer: per voxel size its level-set build, and per offset its trilinear samples of
// the oracle's own upper samples at the same poses, counted as the oracle counts; the sub-voxel
// oracle's rows and the oracle's build row name it and carry OpenVDB's median over theirs.
// --no-openvdb drops every row of it.
TEST(BenchCommandTest, OpenVdbRowsSampleTheOracleSamplesAndCountAlike) {
  if (!kBuiltWithOpenVdb) GTEST_SKIP() << "occlude was built without OpenVDB";
  TempDir tmp;
  const CommandRun r = Occlude(
      "bench --synthetic 5000 --voxel 0.4 --reps 1 --rounds 1 --offsets 0.5,0,-0.1,-0.2 --no-fcl "
      "--out " +
      (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::map<std::string, CsvRow> ist, openvdb;  // by query and offset ("build" for the build)
  for (const auto& row : ReadCsvRows(tmp / "out" / "bench.csv")) {
    const std::string key = row.at("query") + "@" + row.at("offset_mm");
    if (row.at("method") == "openvdb") {
      EXPECT_EQ(row.at("variant"), "levelset");
      EXPECT_EQ(row.at("voxel_mm"), "0.400");
      EXPECT_TRUE(openvdb.emplace(key, row).second) << key;
    }
    if (row.at("method") == "ist" && row.at("variant") == "explicit" &&
        (row.at("query") == "oracle-subvoxel" || row.at("structure") == "oracle")) {
      ist.emplace(key, row);
    }
  }
  ASSERT_EQ(openvdb.size(), 5u);  // the build and four offsets
  ASSERT_TRUE(openvdb.count("build@"));
  EXPECT_EQ(openvdb.at("build@").at("structure"), "grid");
  EXPECT_GT(Value(openvdb.at("build@"), "bytes"), 0.0);
  auto expect_speedup = [&](const std::string& key, const char* reference) {
    const CsvRow& ours = ist.at(key);
    EXPECT_EQ(ours.at("openvdb_reference"), reference) << key;
    const double ratio = Value(openvdb.at(key), "median_us") / Value(ours, "median_us");
    // Printed with 2 decimals (the medians too): equal within that rounding.
    EXPECT_NEAR(Value(ours, "speedup_vs_openvdb"), ratio, 0.006 + 0.01 * ratio) << key;
  };
  expect_speedup("build@", "levelset:build");
  bool commands_oracle = false;  // the oracle as the commands build it: against OpenVDB's too
  for (const auto& row : ReadCsvRows(tmp / "out" / "bench.csv")) {
    if (row.at("structure") != "commands-oracle") continue;
    commands_oracle = true;
    EXPECT_EQ(row.at("openvdb_reference"), "levelset:build");
    const double ratio = Value(openvdb.at("build@"), "median_us") / Value(row, "median_us");
    EXPECT_NEAR(Value(row, "speedup_vs_openvdb"), ratio, 0.006 + 0.01 * ratio);
  }
  EXPECT_TRUE(commands_oracle);
  for (const char* offset : {"0.500", "0.000", "-0.100", "-0.200"}) {
    const std::string key = std::string("oracle-subvoxel@") + offset;
    ASSERT_TRUE(openvdb.count(key) && ist.count(key)) << key;
    expect_speedup(key, "levelset:oracle-subvoxel");
    const CsvRow &a = ist.at(key), &b = openvdb.at(key);
    // The same samples at the same (on-axis) pose, counted alike; the two distances differ by
    // how each is interpolated: the oracle's field and OpenVDB's grid both hold exact distances
    // at their corners, but on lattices offset from each other, and trilinear values between
    // them err differently on the curved surface (up to a few hundredths of a mm at 0.4 mm
    // voxels). Only samples within that error of the contact band's edges (0 and 0.1 mm) or of
    // the surface can count differently: a few % of the contacts (3.9 % at the bite, measured).
    // The samples near the surface may also swap contact for penetration: both areas are held
    // to a share of the area near the surface (contact + penetration).
    const double contacts = Value(a, "pairs");
    const double near_mm2 = Value(a, "contact_area_mm2") + Value(a, "penetration_area_mm2");
    EXPECT_NEAR(Value(b, "pairs"), contacts, 3.0 + 0.06 * contacts) << key;
    EXPECT_NEAR(Value(b, "contact_area_mm2"), Value(a, "contact_area_mm2"), 0.1 + 0.06 * near_mm2)
        << key;
    EXPECT_NEAR(Value(b, "penetration_area_mm2"), Value(a, "penetration_area_mm2"),
                0.1 + 0.06 * near_mm2)
        << key;
    EXPECT_NEAR(Value(b, "max_penetration_mm"), Value(a, "max_penetration_mm"), 0.04) << key;
  }
  EXPECT_GT(Value(ist.at("oracle-subvoxel@-0.200"), "pairs"), 100.0);  // the bite touches
  EXPECT_EQ(ist.at("oracle-subvoxel@0.500").at("pairs"), "0");
  const std::string summary = ReadFileText(tmp / "out" / "bench-summary.txt");
  EXPECT_NE(summary.find("OpenVDB levelset:oracle-subvoxel"), std::string::npos) << summary;
  EXPECT_NE(summary.find("openvdb levelset 0.40mm grid"), std::string::npos) << summary;
  EXPECT_GT(PngFileSize(tmp / "out" / "oracle-0.40mm.png").first, 400);

  const CommandRun without = Occlude(
      "bench --synthetic 5000 --voxel 0.8 --reps 1 --rounds 1 --offsets 0 --no-fcl "
      "--no-openvdb --out " +
      (tmp / "without").string());
  ASSERT_EQ(without.exit_code, 0) << without.output;
  for (const auto& row : ReadCsvRows(tmp / "without" / "bench.csv")) {
    EXPECT_NE(row.at("method"), "openvdb");
    EXPECT_TRUE(row.at("openvdb_reference").empty());
  }
}

TEST(BenchCommandTest, HapticLoopReportsEveryTickAndThePercentiles) {
  TempDir tmp;
  const CommandRun r =
      Occlude("bench --synthetic 5000 --haptic --voxel 0.8 --seconds 0.05 --periods 1000 --out " +
              (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = ReadCsvRows(tmp / "out" / "haptic.csv");
  std::set<std::string> queries;
  for (const auto& row : rows) {
    queries.insert(row.at("method") + ":" + row.at("query"));
    EXPECT_EQ(row.at("ticks_planned"), "51");
    EXPECT_GT(std::stoi(row.at("ticks")), 0);
    EXPECT_LE(std::stoi(row.at("misses")), std::stoi(row.at("ticks")));
    EXPECT_LE(std::stod(row.at("p50_us")), std::stod(row.at("p99_us")));
    EXPECT_LE(std::stod(row.at("p99_us")), std::stod(row.at("p999_us")));
    EXPECT_LE(std::stod(row.at("p999_us")), std::stod(row.at("max_us")));
    // Every miss is either a wall-clock stall or the query's.
    EXPECT_EQ(std::stoi(row.at("misses_stalled")) + std::stoi(row.at("misses_query")),
              std::stoi(row.at("misses")));
    EXPECT_GE(std::stod(row.at("off_cpu_max_us")), 0.0);
  }
  for (const char* q :
       {"ist:oracle-voxel", "ist:oracle-subvoxel", "ist:oracle-exact", "ist:boolean"}) {
    EXPECT_TRUE(queries.count(q)) << q;
  }
  EXPECT_GT(PngFileSize(tmp / "out" / "haptic-1000us.png").first, 400);
}

TEST(BenchCommandTest, BadInputsWriteNothing) {
  TempDir tmp;
  CommandRun r = Occlude("bench --case " + (tmp / "missing").string() + " --out " +
                         (tmp / "a" / "out").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("missing"), std::string::npos) << r.output;
  EXPECT_TRUE(EmptyOrMissing(tmp / "a" / "out"));
  std::filesystem::create_directories(tmp / "empty_case");
  r = Occlude("bench --case " + (tmp / "empty_case").string() + " --out " + (tmp / "b").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("lower.stl"), std::string::npos) << r.output;
  EXPECT_TRUE(EmptyOrMissing(tmp / "b"));
  r = Occlude("bench --synthetic 5000 --voxel 0 --out " + (tmp / "c").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--voxel"), std::string::npos) << r.output;
  EXPECT_TRUE(EmptyOrMissing(tmp / "c"));
  r = Occlude("bench --out " + (tmp / "d").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(EmptyOrMissing(tmp / "d"));
}

// --- --paper ----------------------------------------------------------------------------------

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

// --- --accuracy -------------------------------------------------------------------------------

// Small on purpose (seconds, also under the sanitizers): two voxel sizes, three
// poses from 0.2 mm interpenetrating to 0.1 mm open, so that every pose touches.
const char* kRun =
    "bench --accuracy --voxel 0.8,0.4 --poses 3 --reps 1 --offset-range -0.2,0.1 "
    "--truth-spacing 0.2";

class AccuracyCommandTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    WriteSphereOnBoxCase(*dir_ / "case");
    run_ = new CommandRun(Occlude(std::string(kRun) + " --case " + (*dir_ / "case").string() +
                                  " --out " + (*dir_ / "out").string()));
  }
  static void TearDownTestSuite() {
    delete run_;
    delete dir_;
  }
  void SetUp() override { ASSERT_EQ(run_->exit_code, 0) << run_->output; }
  static std::filesystem::path Out(const std::string& file) { return *dir_ / "out" / file; }
  // Rows keyed by "method,variant,voxel_mm,query,level".
  static std::map<std::string, CsvRow> Rows() {
    std::map<std::string, CsvRow> rows;
    for (const CsvRow& r : ReadCsvRows(Out("accuracy.csv"))) {
      const std::string key = r.at("method") + "," + r.at("variant") + "," + r.at("voxel_mm") +
                              "," + r.at("query") + "," + r.at("level");
      EXPECT_TRUE(rows.emplace(key, r).second) << "duplicate row " << key;
    }
    return rows;
  }
  static TempDir* dir_;
  static CommandRun* run_;
};
TempDir* AccuracyCommandTest::dir_ = nullptr;
CommandRun* AccuracyCommandTest::run_ = nullptr;

TEST_F(AccuracyCommandTest, HasTheDocumentedColumnsAndDefinitions) {
  std::vector<std::string> header;
  ReadCsvRows(Out("accuracy.csv"), &header);
  for (const char* column :
       {"method", "variant", "voxel_mm", "level", "median_us", "p95_err_mm", "max_err_mm", "missed",
        "false_contacts", "query", "median_err_mm", "truth_contacts", "missed_frac",
        "missed_half_band", "false_frac", "pen_err_median_mm", "pen_err_max_mm", "pareto"}) {
    EXPECT_NE(std::find(header.begin(), header.end(), column), header.end()) << column;
  }
  const std::string text = ReadFileText(Out("accuracy.csv"));
  for (const char* words : {"# Ground truth:", "# Truth contact:", "# Missed:", "machine:"}) {
    EXPECT_NE(text.find(words), std::string::npos) << words;
  }
}

TEST_F(AccuracyCommandTest, HasOneRowPerMethodLevelAndVoxelSize) {
  const auto rows = Rows();
  std::set<std::string> expected;
  for (const char* v : {"0.800", "0.400"}) {
    for (const char* level : {"voxel", "subvoxel", "exact"})
      expected.insert(std::string("ist,explicit,") + v + ",oracle," + level);
    for (const char* variant : {"simple", "optimized", "explicit"})
      for (const char* level : {"voxel", "exact"})
        expected.insert(std::string("ist,") + variant + "," + v + ",pairs," + level);
  }
  if (kBuiltWithFcl) {
    expected.insert("fcl,obb,,collide-all,exact");
    expected.insert("fcl,obbrss,,collide-all,exact");
    expected.insert("fcl,obbrss,,distance,exact");
  }
  std::set<std::string> got;
  for (const auto& [key, row] : rows) got.insert(key);
  EXPECT_EQ(got, expected);
  for (const auto& [key, row] : rows) {
    EXPECT_GT(Value(row, "median_us"), 0.0) << key;
    EXPECT_EQ(row.at("poses"), "3") << key;
  }
}

TEST_F(AccuracyCommandTest, ChartsArePngsAndTheTableParses) {
  for (const char* chart : {"accuracy.png", "accuracy-max.png"}) {
    const auto size = PngFileSize(Out(chart));
    EXPECT_GT(size.first, 800) << chart;
    EXPECT_GT(size.second, 500) << chart;
  }
  const auto j = nlohmann::json::parse(ReadFileText(Out("accuracy-table.json")));
  ASSERT_EQ(j.at("oracle").size(), 6u);  // 2 voxel sizes x 3 levels
  double last = 0.0;
  for (const auto& e : j.at("oracle")) {
    EXPECT_GE(e.at("median_us").get<double>(), last);  // sorted: the planner takes the first fit
    last = e.at("median_us").get<double>();
    EXPECT_TRUE(e.contains("p95_err_mm") && e.contains("voxel_mm") && e.contains("level"));
  }
}

TEST_F(AccuracyCommandTest, AccuracyNumbersAreSane) {
  auto rows = Rows();
  auto at = [&](const std::string& key) -> const CsvRow& { return rows.at(key); };
  ASSERT_GT(Value(at("ist,explicit,0.400,oracle,exact"), "truth_contacts"), 0.0);
  for (const char* v : {"0.800", "0.400"}) {
    const std::string o = std::string("ist,explicit,") + v + ",oracle,";
    // The exact level is the ground truth's own definition: zero error.
    EXPECT_LT(Value(at(o + "exact"), "max_err_mm"), kExactMm) << v;
    EXPECT_EQ(at(o + "exact").at("false_contacts"), "0") << v;
    // Interpolating beats the voxel centre value.
    EXPECT_LT(Value(at(o + "subvoxel"), "p95_err_mm"), Value(at(o + "voxel"), "p95_err_mm")) << v;
    for (const char* variant : {"simple", "optimized", "explicit"}) {
      const std::string p = std::string("ist,") + variant + "," + v + ",pairs,";
      // Voxel pairs are conservative: a truth contact within delta of the
      // lower surface (|d*| <= delta / 2 here) has its voxel paired; exact
      // pairs then find its triangle, and each claimed closest point is at most
      // its claimed (unsigned) distance away. (Deeper interpenetration is
      // invisible to both: they see surfaces within delta, not the inside.)
      EXPECT_EQ(at(p + "voxel").at("missed_half_band"), "0") << p;
      EXPECT_EQ(at(p + "exact").at("missed_half_band"), "0") << p;
      EXPECT_EQ(at(p + "exact").at("false_contacts"), "0") << p;
      // The sphere modes change the work, never the answer.
      for (const char* column : {"p95_err_mm", "max_err_mm", "missed", "false_contacts"}) {
        EXPECT_EQ(at(p + "voxel").at(column),
                  at(std::string("ist,explicit,") + v + ",pairs,voxel").at(column));
      }
    }
  }
  // Analytic on the box's flat top: the voxel level reads the distance at the
  // centre of the lower voxel holding the point, at most half a voxel away along
  // the normal; trilinear interpolation of a linear distance is exact (up to the
  // float storage of the corner values, 1e-5 mm here).
  EXPECT_LE(Value(at("ist,explicit,0.800,oracle,voxel"), "max_err_mm"), 0.4 + kExactMm);
  EXPECT_LE(Value(at("ist,explicit,0.400,oracle,voxel"), "max_err_mm"), 0.2 + kExactMm);
  EXPECT_LT(Value(at("ist,explicit,0.400,oracle,subvoxel"), "max_err_mm"), 1e-5);
  // Coarser voxels: larger errors at the voxel level (oracle and pairs).
  EXPECT_GT(Value(at("ist,explicit,0.800,oracle,voxel"), "p95_err_mm"),
            Value(at("ist,explicit,0.400,oracle,voxel"), "p95_err_mm"));
  EXPECT_GT(Value(at("ist,explicit,0.800,pairs,voxel"), "p95_err_mm"),
            Value(at("ist,explicit,0.400,pairs,voxel"), "p95_err_mm"));
  int pareto = 0;
  for (const auto& [key, row] : rows) pareto += row.at("pareto") == "1";
  EXPECT_GE(pareto, 1);
}

TEST(AccuracyCommandErrorsTest, BadOptionsNameTheOptionAndWriteNothing) {
  TempDir tmp;
  CommandRun r =
      Occlude("bench --accuracy --synthetic 5000 --offset-range 1,0 --out " + (tmp / "a").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--offset-range"), std::string::npos) << r.output;
  EXPECT_TRUE(EmptyOrMissing(tmp / "a"));
  r = Occlude("bench --accuracy --mesh " + (tmp / "x.stl").string() + " --out " +
              (tmp / "b").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--mesh"), std::string::npos) << r.output;
  EXPECT_TRUE(EmptyOrMissing(tmp / "b"));
  r = Occlude("bench --accuracy --paper --synthetic 5000 --out " + (tmp / "c").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(EmptyOrMissing(tmp / "c"));
}

}  // namespace
}  // namespace occlude::test
