// Accuracy-driven resolution: the rule (fastest measured setting whose 95th-percentile
// contact-distance error meets the wanted accuracy and that missed no contact within half
// the band) against a brute-force pick over random tables; the built-in table parses and
// is the measured one; unmet accuracies fall back to the most accurate setting, flagged;
// the case config picks through it, takes its own table, and reports bad tables by key.
#include "config/resolution_choice.h"

#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "base/user_error.h"
#include "config/case_config.h"
#include "occlude/io/mesh_io.h"
#include "test_common.h"

namespace occlude::test {
namespace {

using app::ResolutionOption;
using app::ResolutionTable;
using collision::AccuracyLevel;

std::string RowJson(double voxel, const char* level, double us, double p95, double max,
                    long missed) {
  return "{\"method\":\"ist\",\"variant\":\"explicit\",\"query\":\"oracle\",\"voxel_mm\":" +
         std::to_string(voxel) + ",\"level\":\"" + level +
         "\",\"median_us\":" + std::to_string(us) + ",\"p95_err_mm\":" + std::to_string(p95) +
         ",\"max_err_mm\":" + std::to_string(max) +
         ",\"missed_half_band\":" + std::to_string(missed) + "}";
}

TEST(ResolutionChoiceTest, BuiltInTableIsTheMeasuredOne) {
  const ResolutionTable& table = app::DefaultResolutionTable();
  EXPECT_EQ(table.case_name, "a-bite-3shape");
  ASSERT_GE(table.options.size(), 6u);
  for (std::size_t i = 1; i < table.options.size(); ++i) {
    EXPECT_LE(table.options[i - 1].median_us, table.options[i].median_us);  // fastest first
  }
  for (const ResolutionOption& o : table.options) {
    EXPECT_GT(o.voxel_mm, 0.0);
    EXPECT_GE(o.p95_err_mm, 0.0);
    EXPECT_GE(o.max_err_mm, o.p95_err_mm);
    if (o.level == AccuracyLevel::kExact) {
      EXPECT_EQ(o.p95_err_mm, 0.0);
    }
  }
}

TEST(ResolutionChoiceTest, FastestSettingThatMeetsTheAccuracyAgainstBruteForce) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> us(10, 50000), err(0.0, 0.3), wanted(0.001, 0.3);
  const char* levels[] = {"voxel", "subvoxel", "exact"};
  for (int trial = 0; trial < 200; ++trial) {
    std::string json = "{\"case\":\"t\",\"oracle\":[";
    std::vector<ResolutionOption> rows;
    const int n = 1 + static_cast<int>(rng() % 8);
    for (int i = 0; i < n; ++i) {
      ResolutionOption o;
      o.voxel_mm = 0.1 * (1 + static_cast<int>(rng() % 8));
      const int l = static_cast<int>(rng() % 3);
      o.level = static_cast<AccuracyLevel>(l);
      o.median_us = us(rng);
      o.p95_err_mm = err(rng);
      o.max_err_mm = o.p95_err_mm * 1.5;
      o.missed_half_band = rng() % 3 == 0 ? static_cast<long>(rng() % 100) : 0;
      rows.push_back(o);
      json += (i ? "," : "") + RowJson(o.voxel_mm, levels[l], o.median_us, o.p95_err_mm,
                                       o.max_err_mm, o.missed_half_band);
    }
    json += "]}";
    const ResolutionTable table = app::ParseResolutionTable(json, "random table");
    const double a = wanted(rng);
    const app::ResolutionChoice c = app::ChooseResolution(a, table);
    // Brute force: every row meeting the accuracy, then the fastest of them.
    const ResolutionOption* best = nullptr;
    for (const ResolutionOption& o : rows) {
      // (the JSON round trip prints 6 decimals)
      const double p95 = std::stod(std::to_string(o.p95_err_mm));
      if (p95 <= a && o.missed_half_band == 0 && (!best || o.median_us < best->median_us))
        best = &o;
    }
    if (best) {
      EXPECT_TRUE(c.met) << trial;
      EXPECT_NEAR(c.chosen.median_us, best->median_us, 1e-6) << trial;
      EXPECT_LE(c.chosen.p95_err_mm, a);
      EXPECT_EQ(c.chosen.missed_half_band, 0);
    } else {
      EXPECT_FALSE(c.met) << trial;
      for (const ResolutionOption& o : table.options) EXPECT_GE(o.p95_err_mm, c.chosen.p95_err_mm);
      EXPECT_NE(c.Describe().find("no measured setting reaches"), std::string::npos);
    }
  }
}

TEST(ResolutionChoiceTest, TighterAccuracyNeverPicksALessAccurateSetting) {
  const ResolutionTable& table = app::DefaultResolutionTable();
  double previous_p95 = 1e9, previous_us = 0.0;
  for (const double a : {0.5, 0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001}) {
    const app::ResolutionChoice c = app::ChooseResolution(a, table);
    ASSERT_TRUE(c.met) << a;  // the exact level meets any accuracy
    EXPECT_LE(c.chosen.p95_err_mm, a);
    EXPECT_LE(c.chosen.p95_err_mm, previous_p95 + 1e-12) << a;
    EXPECT_GE(c.chosen.median_us, previous_us - 1e-9) << a;  // accuracy costs time
    previous_p95 = c.chosen.p95_err_mm;
    previous_us = c.chosen.median_us;
  }
}

TEST(ResolutionChoiceTest, ExplicitVoxelKeepsItAndFindsItsMeasurement) {
  const ResolutionTable& table = app::DefaultResolutionTable();
  const app::ResolutionChoice c = app::ExplicitResolution(0.2, table);
  EXPECT_TRUE(c.explicit_voxel);
  EXPECT_DOUBLE_EQ(c.chosen.voxel_mm, 0.2);
  EXPECT_EQ(c.chosen.level, AccuracyLevel::kSubVoxel);
  EXPECT_TRUE(c.measured);
  const app::ResolutionChoice odd = app::ExplicitResolution(0.33, table);
  EXPECT_DOUBLE_EQ(odd.chosen.voxel_mm, 0.33);
  EXPECT_FALSE(odd.measured);
  EXPECT_EQ(odd.Describe().find("measured"), std::string::npos);
}

TEST(ResolutionChoiceTest, BadTablesNameTheirSource) {
  for (const std::string& text :
       {std::string("not json"), std::string("{\"oracle\": 3}"), std::string("{\"oracle\": []}"),
        std::string("{\"oracle\": [") + RowJson(0.2, "fine", 1, 0.1, 0.1, 0) + "]}"}) {
    try {
      app::ParseResolutionTable(text, "my/table.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const app::UserError& e) {
      EXPECT_NE(std::string(e.what()).find("my/table.json"), std::string::npos) << e.what();
    }
  }
}

TEST(ResolutionChoiceTest, CaseConfigPicksFromTheBuiltInOrItsOwnTable) {
  TempDir tmp;
  const std::string synthetic = "[synthetic]\ntriangles = 5000\n";
  auto load = [&](const std::string& text) {
    std::ofstream(tmp.path() / "case.toml") << text;
    return app::LoadCaseConfig(tmp.path() / "case.toml");
  };
  // The built-in table: the fastest measured setting within the default 0.02 mm.
  const app::CaseConfig d = load(synthetic);
  const app::ResolutionChoice expect = app::ChooseResolution(0.02, app::DefaultResolutionTable());
  EXPECT_DOUBLE_EQ(d.VoxelSizeMm(), expect.chosen.voxel_mm);
  EXPECT_EQ(d.OracleLevel(), expect.chosen.level);
  // Its own table: a 0.5 mm sub-voxel row meets 0.05 mm there and is fastest.
  std::ofstream(tmp.path() / "t.json")
      << "{\"case\":\"mine\",\"oracle\":[" << RowJson(0.5, "subvoxel", 100, 0.03, 0.05, 0) << ","
      << RowJson(0.1, "subvoxel", 900, 0.004, 0.01, 0) << "]}";
  const app::CaseConfig own =
      load(synthetic + "[accuracy]\naccuracy_mm = 0.05\ntable = \"t.json\"\n");
  EXPECT_DOUBLE_EQ(own.VoxelSizeMm(), 0.5);
  const app::CaseConfig tight =
      load(synthetic + "[accuracy]\naccuracy_mm = 0.01\ntable = \"t.json\"\n");
  EXPECT_DOUBLE_EQ(tight.VoxelSizeMm(), 0.1);
  // voxel_mm overrides.
  EXPECT_DOUBLE_EQ(
      load(synthetic + "[accuracy]\nvoxel_mm = 0.3\ntable = \"t.json\"\n").VoxelSizeMm(), 0.3);
  // A missing table names the key.
  try {
    load(synthetic + "[accuracy]\ntable = \"nope.json\"\n");
    ADD_FAILURE() << "missing table accepted";
  } catch (const app::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("accuracy.table"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace occlude::test
