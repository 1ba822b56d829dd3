// `occlude propose` through the real binary on the smallest synthetic pair: it finds the bite
// again from a perturbed start and writes the K proposals and the report; the same inputs, seed
// and threads give byte-identical results; the memory guard names a voxel size that fits; bad
// solver settings are one-line errors naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "bench_files.h"
#include "case_run.h"
#include "config/pose_file.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::app {
namespace {

TEST(ProposeCommandTest, FindsTheBiteAndWritesProposalsAndReport) {
  test::TempDir tmp;
  Write(tmp / "case.toml", Config(tmp / "out"));
  const test::CommandRun r = test::Occlude("propose " + (tmp / "case.toml").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"report.html", "metrics.json", "pose.json", "proposals.json",
                        "lower_map.png", "upper_map.png", "frontal.png", "lateral.png",
                        "upper_at_pose.stl", "proposals/proposal-1.json"}) {
    EXPECT_TRUE(std::filesystem::exists(tmp / "out" / f)) << f;
  }
  const Eigen::Isometry3d best = ReadPoseFile(tmp / "out" / "proposals" / "proposal-1.json");
  // The synthetic bite is X_LU = identity; the pivot lies near the origin, so the translation
  // of X_LU is close to the displacement there (rotations are well under a degree).
  EXPECT_LT(TranslationNorm(best), kFoundMm) << best.matrix();
  const json proposals = ReadJson(tmp / "out" / "proposals.json");
  ASSERT_GE(proposals["proposals"].size(), 1u);
  EXPECT_LE(proposals["proposals"].size(), 2u);
  EXPECT_LE(proposals["proposals"][0]["constrained_penetration_mm"].get<double>(), 0.05 + 0.004);
  EXPECT_GT(proposals["proposals"][0]["contact_area_mm2"].get<double>(), 1.0);
  const json metrics = ReadJson(tmp / "out" / "metrics.json");
  EXPECT_EQ(metrics["search"]["command"], "propose");
  // The clinical relationships of each proposal; the report's are those of proposal 1.
  for (const json& p : proposals["proposals"])
    EXPECT_TRUE(p["relationships"].contains("overjet_mm"));
  EXPECT_EQ(metrics["relationships"], proposals["proposals"][0]["relationships"]);
  EXPECT_NE(test::ReadFileText(tmp / "out" / "report.html").find("<h2>Clinical relationships</h2>"),
            std::string::npos);
  EXPECT_NE(r.output.find("report of #1"), std::string::npos) << r.output;
}

std::string ReadText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Removes every timing: keys in seconds end in "_s" (timings_s, build_s, select_s, ...).
void EraseTimings(json* j) {
  if (j->is_object()) {
    for (auto it = j->begin(); it != j->end();) {
      const std::string& key = it.key();
      if (key.size() > 2 && key.compare(key.size() - 2, 2, "_s") == 0) {
        it = j->erase(it);
      } else {
        EraseTimings(&it.value());
        ++it;
      }
    }
  } else if (j->is_array()) {
    for (json& e : *j) EraseTimings(&e);
  }
}

// metrics.json without its timings (the only part that may differ between runs).
std::string WithoutTimings(const std::filesystem::path& file) {
  json j = ReadJson(file);
  EXPECT_TRUE(j.contains("timings_s")) << file;
  EraseTimings(&j);
  EXPECT_FALSE(j.contains("timings_s"));
  return j.dump(1);
}

// Determinism: the same inputs, seed and thread count give byte-identical pose.json and
// metrics.json (timings excluded), and identical proposals, from two separate processes.
TEST(ProposeCommandTest, SameInputsSeedAndThreadsGiveByteIdenticalResults) {
  test::TempDir tmp;
  Write(tmp / "case.toml", Config(tmp / "out", "[0.0, 0.0, 0.0]", "seed = 7\nthreads = 2\n"));
  for (const char* out : {"a", "b"}) {
    const test::CommandRun r =
        test::Occlude("propose " + (tmp / "case.toml").string() + " --out " + (tmp / out).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const std::string pose_a = ReadText(tmp / "a" / "pose.json");
  ASSERT_FALSE(pose_a.empty());
  EXPECT_EQ(pose_a, ReadText(tmp / "b" / "pose.json"));
  for (const char* file : {"upper_at_pose.stl", "upper_at_pose.ply", "lower.ply"}) {
    EXPECT_EQ(ReadText(tmp / "a" / file), ReadText(tmp / "b" / file)) << file;
  }
  EXPECT_EQ(WithoutTimings(tmp / "a" / "metrics.json"), WithoutTimings(tmp / "b" / "metrics.json"));
  EXPECT_EQ(ReadText(tmp / "a" / "proposals" / "proposal-1.json"),
            ReadText(tmp / "b" / "proposals" / "proposal-1.json"));
}

// The memory guard of a session asks about other voxel sizes than the config's: over the
// budget at 0.2 mm (about 480 MB estimated for the 20k pair), it names a coarser one that fits
// (the estimate follows the voxel size).
TEST(ProposeCommandTest, MemoryGuardNamesACoarserVoxelThatFits) {
  test::TempDir tmp;
  Write(tmp / "case.toml",
        "[synthetic]\ntriangles = 20000\n[output]\nfolder = \"" + (tmp / "out").string() + "\"\n");
  const test::CommandRun r =
      test::Occlude("propose " + (tmp / "case.toml").string() + " --memory-budget-mb 400");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("the smallest voxel size that fits is about"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(tmp / "out" / "pose.json"));
}

TEST(ProposeCommandTest, BadSolverSettingsAreOneLineErrorsNamingTheKey) {
  test::TempDir tmp;
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"[solver.options]\nglobal_sample = 4\n", "did you mean 'global_samples'"},
      {"[solver.options]\nnlopt_local = \"simplex\"\n", "solver.options.nlopt_local"},
      {"[solver.options]\nmax_evaluations = \"many\"\n", "must be an integer"}};
  for (const auto& [extra, expected] : bad) {
    Write(tmp / "case.toml", Config(tmp / "out", "[0.0, 0.0, 0.0]", extra));
    const test::CommandRun r = test::Occlude("propose " + (tmp / "case.toml").string());
    EXPECT_NE(r.exit_code, 0) << extra;
    EXPECT_NE(r.output.find(expected), std::string::npos) << extra << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(std::filesystem::exists(tmp / "out" / "report.html"));
  }
  Write(tmp / "case.toml",
        "[synthetic]\ntriangles = 5000\n[solver]\nname = \"simplex\"\n[output]\nfolder = \"" +
            (tmp / "out").string() + "\"\n");
  const test::CommandRun r = test::Occlude("propose " + (tmp / "case.toml").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("solver.name"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace occlude::app
