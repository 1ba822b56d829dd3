// `occlude bench`: the CSV has the documented columns and one row per method,
// variant, voxel size, query kind and offset; the charts are PNG files; the
// poses are seeded, jittered within bounds and identical for every method; the
// haptic loop reports every tick; bad inputs write nothing.
#include "bench/bench.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "bench/bench_poses_internal.h"
#include "bench/fcl_peer.h"
#include "chart/chart.h"
#include "occlude/io/synthetic_jaws.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::test {
namespace {

std::string ReadText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> Split(const std::string& line, char sep = ',') {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, sep)) out.push_back(cell);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

// Rows of a CSV as maps from column name to cell.
std::vector<std::map<std::string, std::string>> ReadCsv(const std::filesystem::path& file) {
  std::istringstream in(ReadText(file));
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = Split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = Split(line);
    EXPECT_EQ(cells.size(), header.size()) << line;
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < std::min(cells.size(), header.size()); ++i)
      row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

// Width and height from a PNG's IHDR chunk; {0, 0} when not a PNG.
std::pair<int, int> PngSize(const std::string& bytes) {
  const std::string signature = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 24 || bytes.compare(0, 8, signature) != 0 ||
      bytes.compare(12, 4, "IHDR") != 0) {
    return {0, 0};
  }
  auto be32 = [&](std::size_t at) {
    int v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  return {be32(16), be32(20)};
}

TEST(BenchCommandTest, WritesOneRowPerMethodQueryAndOffsetWithTheDocumentedColumns) {
  TempDir tmp;
  const CommandRun r = Occlude(
      "bench --synthetic 5000 --voxel 0.8,0.4 --reps 1 --rounds 2 --offsets 1,0,-0.1 --out " +
      (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string header = ReadText(tmp / "out" / "bench.csv").substr(0, 200);
  EXPECT_EQ(header.rfind(
                "method,variant,voxel_mm,query,offset_mm,median_us,max_us,rate_hz,pairs,bytes", 0),
            0u)
      << header;
  const auto rows = ReadCsv(tmp / "out" / "bench.csv");
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
  if (app::FclPeer::Available()) {
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
    const auto size = PngSize(ReadText(tmp / "out" / chart));
    EXPECT_GT(size.first, 400) << chart;
    EXPECT_GT(size.second, 300) << chart;
  }
  EXPECT_NE(ReadText(tmp / "out" / "bench-summary.txt").find("cores"), std::string::npos);
}

TEST(BenchCommandTest, HapticLoopReportsEveryTickAndThePercentiles) {
  TempDir tmp;
  const CommandRun r =
      Occlude("bench --synthetic 5000 --haptic --voxel 0.8 --seconds 0.05 --periods 1000 --out " +
              (tmp / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = ReadCsv(tmp / "out" / "haptic.csv");
  std::set<std::string> queries;
  for (const auto& row : rows) {
    queries.insert(row.at("method") + ":" + row.at("query"));
    EXPECT_EQ(row.at("ticks_planned"), "51");
    EXPECT_GT(std::stoi(row.at("ticks")), 0);
    EXPECT_LE(std::stoi(row.at("misses")), std::stoi(row.at("ticks")));
    EXPECT_LE(std::stod(row.at("p50_us")), std::stod(row.at("p99_us")));
    EXPECT_LE(std::stod(row.at("p99_us")), std::stod(row.at("p999_us")));
    EXPECT_LE(std::stod(row.at("p999_us")), std::stod(row.at("max_us")));
  }
  for (const char* q :
       {"ist:oracle-voxel", "ist:oracle-subvoxel", "ist:oracle-exact", "ist:boolean"}) {
    EXPECT_TRUE(queries.count(q)) << q;
  }
  EXPECT_GT(PngSize(ReadText(tmp / "out" / "haptic-1000us.png")).first, 400);
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

app::BenchCase SyntheticCase() {
  io::SyntheticJawOptions options;
  options.triangles_per_jaw = 5000;
  const io::SyntheticJawPair jaws = io::MakeSyntheticJawPair(options);
  app::BenchCase bc;
  bc.lower_L = std::make_shared<io::TriangleMesh>(jaws.lower_L);
  bc.upper_U = std::make_shared<io::TriangleMesh>(jaws.upper_U);
  bc.X_LU_ref = jaws.X_LU;
  bc.axis_L = jaws.occlusal_axis_L;
  return bc;
}

TEST(BenchPosesTest, SweepPosesAreSeededAndJitteredWithinBounds) {
  const app::BenchCase bc = SyntheticCase();
  const std::vector<double> offsets = {2.0, 0.0, -0.2};
  const auto a = app::SweepPoses(bc, offsets, 20, 0.2, 0.05, 7);
  const auto b = app::SweepPoses(bc, offsets, 20, 0.2, 0.05, 7);
  const auto c = app::SweepPoses(bc, offsets, 20, 0.2, 0.05, 8);
  ASSERT_EQ(a.size(), offsets.size());
  const Eigen::Vector3d pivot_L = app::UpperCentroidL(bc);
  for (std::size_t k = 0; k < offsets.size(); ++k) {
    ASSERT_EQ(a[k].size(), 20u);
    const Eigen::Isometry3d exact = Eigen::Translation3d(offsets[k] * bc.axis_L) * bc.X_LU_ref;
    EXPECT_TRUE(a[k][0].isApprox(exact, 1e-12));
    for (std::size_t r = 0; r < 20; ++r) {
      EXPECT_TRUE(a[k][r].isApprox(b[k][r], 0.0));
      const Eigen::Isometry3d delta = a[k][r] * exact.inverse();  // jitter, in L
      const double angle_deg = Eigen::AngleAxisd(delta.linear()).angle() * 180.0 / 3.14159265358979;
      EXPECT_LE(angle_deg, 0.2 + 1e-9);
      // The centroid moves across the axis by the translation jitter only.
      const Eigen::Vector3d moved =
          delta * (pivot_L + offsets[k] * bc.axis_L) - (pivot_L + offsets[k] * bc.axis_L);
      EXPECT_LE(moved.norm(), 0.05 + 1e-9);
      EXPECT_NEAR(moved.dot(bc.axis_L), 0.0, 1e-9);
      if (r > 0) {
        EXPECT_FALSE(a[k][r].isApprox(c[k][r], 1e-12));
      }
    }
  }
}

TEST(BenchPosesTest, HapticTrajectoryDescendsThenSlidesAtTheContactHeight) {
  const app::BenchCase bc = SyntheticCase();
  int calls = 0;
  const app::HapticTrajectory trajectory(bc, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(),
                                         2.0, 3, [&](const Eigen::Isometry3d&) {
                                           ++calls;
                                           return 0.05;
                                         });
  EXPECT_EQ(calls, 48);
  const Eigen::Vector3d c0 = app::UpperCentroidL(bc);
  auto height = [&](double t) {
    return (trajectory.At(t) * bc.X_LU_ref.inverse() * c0 - c0).dot(bc.axis_L);
  };
  EXPECT_NEAR(height(0.0), 2.0, 1e-9);
  EXPECT_NEAR(height(0.5), 0.05, 1e-6);
  EXPECT_NEAR(height(1.7), 0.05, 0.01);  // the wobble tilts about the centroid: no lift there
  // Continuous: at a 1 ms tick no point of the jaw jumps by more than 10 um.
  double worst = 0.0;
  for (double t = 0.0; t < 2.0; t += 1e-3) {
    const Eigen::Isometry3d step = trajectory.At(t + 1e-3) * trajectory.At(t).inverse();
    for (const auto& v : bc.upper_U->vertices) {
      const Eigen::Vector3d p = trajectory.At(t) * v;
      worst = std::max(worst, (step * p - p).norm());
      break;
    }
  }
  EXPECT_LT(worst, 0.01);
  // And it slides: lateral motion of at least 0.2 mm in the sliding phase.
  double lateral_min = 1e9, lateral_max = -1e9;
  for (double t = 0.5; t <= 2.0; t += 0.01) {
    const double x = (trajectory.At(t) * bc.X_LU_ref.inverse() * c0 - c0).x();
    lateral_min = std::min(lateral_min, x);
    lateral_max = std::max(lateral_max, x);
  }
  EXPECT_GT(lateral_max - lateral_min, 0.2);
}

TEST(ChartTest, LongSubtitlesWrapAtSpacesWithinTheWidth) {
  const std::string text =
      "a-bite-3shape | 2 cores (AMD EPYC), load 6.20 at start | one core per run | success: within "
      "0.3 mm "
      "and 1 deg of the reference; dashed: of the runs' consensus";
  const int width = 600;
  const std::vector<std::string> lines = app::WrapChartText(text, 0.45, width);
  ASSERT_GE(lines.size(), 2u);
  std::string joined;
  for (const std::string& line : lines) {
    EXPECT_LE(app::ChartTextWidth(line, 0.45), width) << line;
    joined += (joined.empty() ? "" : " ") + line;
  }
  EXPECT_EQ(joined, text);  // nothing lost, words kept whole
  EXPECT_EQ(app::WrapChartText("short", 0.45, width), std::vector<std::string>{"short"});
  EXPECT_TRUE(app::WrapChartText("", 0.45, width).empty());
  const std::string word(200, 'w');  // wider than the width: alone on its line, not cut
  EXPECT_EQ(app::WrapChartText("a " + word + " b", 0.45, width),
            (std::vector<std::string>{"a", word, "b"}));
}

TEST(ChartTest, RendersAPngOfTheRequestedSizeAndRejectsAnEmptyChart) {
  app::LineChart chart;
  chart.title = "t";
  chart.log_y = true;
  chart.width = 640;
  chart.height = 480;
  chart.series.push_back({"a", {0, 1, 2}, {10, 100, 1000}});
  chart.series.push_back(
      {"b", {0, 1, 2}, {5, -1, 50}});  // the negative point is skipped on a log axis
  EXPECT_EQ(PngSize(app::RenderLineChartPng(chart)), std::make_pair(640, 480));
  app::LineChart empty;
  empty.series.push_back({"nothing", {}, {}});
  EXPECT_THROW(app::RenderLineChartPng(empty), std::invalid_argument);
}

}  // namespace
}  // namespace occlude::test
