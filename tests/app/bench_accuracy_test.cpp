// `occlude bench --accuracy` on the small sphere-on-box case (one run shared by
// the tests): every documented column, one row per method / variant / voxel
// size / query / level, PNG charts, the planner's JSON table, and numbers that
// must hold by construction: the exact oracle level has zero error against the
// ground truth, the voxel level errs by at most half a voxel on the flat box
// and interpolation not at all, coarser voxels have larger errors, the voxel-pair
// query misses no contact near the surface (it is conservative) and the exact
// pair query invents none, and the three sphere modes answer alike.
#include "bench/bench_accuracy.h"

#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "bench/fcl_peer.h"
#include "bench_files.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::test {
namespace {

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
  if (app::FclPeer::Available()) {
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

TEST(AccuracyParetoTest, MarksExactlyTheUndominatedRows) {
  auto row = [](double us, double err) {
    app::AccuracyRow r;
    r.us.median = us;
    r.p95_err_mm = err;
    return r;
  };
  std::vector<app::AccuracyRow> rows = {row(10, 1.0), row(20, 0.5),         row(30, 0.7),
                                        row(40, 0.0), row(10, 1.0 + 1e-12), row(5, std::nan("")),
                                        row(1, 0.0)};
  // The fastest, exact row misses 2 of 100 truth contacts within half the band.
  rows[6].truth_half = 100;
  rows[6].missed_half = 2;
  app::MarkPareto(&rows);
  EXPECT_TRUE(rows[0].pareto);
  EXPECT_TRUE(rows[1].pareto);
  EXPECT_FALSE(rows[2].pareto);  // slower and worse than rows[1]
  EXPECT_TRUE(rows[3].pareto);
  EXPECT_TRUE(rows[4].pareto);   // equal to rows[0] up to rounding: neither dominates
  EXPECT_FALSE(rows[5].pareto);  // no error measured
  EXPECT_FALSE(rows[6].pareto);  // misses contacts: off the front, and it dominates nothing
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
