// `occlude propose` and `occlude refine` through the real binary on the smallest synthetic
// pair (known bite at X_LU = identity): propose finds the bite again from a perturbed start
// and writes the K proposals and the report; refine applies [adjust] with a locked degree
// of freedom and says what changed; refine --watch repeats on a save; bad solver settings
// are one-line errors naming the key.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "config/pose_file.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::app {
namespace {

using nlohmann::json;

// Within the success bar of the designed bite.
constexpr double kFoundMm = 0.3;

std::string Config(const std::filesystem::path& out, const std::string& adjust = "[0.0, 0.0, 0.0]",
                   const std::string& extra = "") {
  return "[synthetic]\ntriangles = 5000\n[accuracy]\nvoxel_mm = 0.5\n[solver]\nstarts = "
         "3\nproposals = 2\n" +
         extra +
         "[start]\ntranslation_mm = [0.4, 0.5, -0.3]\nrotation_deg = [0.5, -0.8, 0.4]\n"
         "[adjust]\ntranslation_mm = " +
         adjust + "\n[output]\nfolder = \"" + out.string() + "\"\n";
}

void Write(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

json ReadJson(const std::filesystem::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

double TranslationNorm(const Eigen::Isometry3d& X) { return X.translation().norm(); }

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
  EXPECT_NE(r.output.find("report of #1"), std::string::npos) << r.output;
}

TEST(RefineCommandTest, AppliesTheAdjustmentWithALockedDofAndReports) {
  test::TempDir tmp;
  Write(tmp / "case.toml", Config(tmp / "out"));
  ASSERT_EQ(test::Occlude("propose " + (tmp / "case.toml").string()).exit_code, 0);
  const Eigen::Isometry3d base = ReadPoseFile(tmp / "out" / "pose.json");
  Write(tmp / "case.toml", Config(tmp / "out", "[0.3, 0.0, 0.0]", "[bounds]\nlocked = [\"tx\"]\n"));
  const test::CommandRun r = test::Occlude("refine " + (tmp / "case.toml").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("moved t (0.300,"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("contact"), std::string::npos) << r.output;
  const json refine = ReadJson(tmp / "out" / "refine.json");
  EXPECT_NEAR(refine["moved_from_base"]["translation_mm"][0].get<double>(), 0.3,
              1e-6);  // locked at the adjustment
  EXPECT_TRUE(refine["after"]["feasible"].get<bool>());
  const Eigen::Isometry3d after = ReadPoseFile(tmp / "out" / "pose.json");
  EXPECT_GT((after.translation() - base.translation()).norm(), 0.29);
}

TEST(RefineCommandTest, WatchRefinesAgainOnEverySave) {
  test::TempDir tmp;
  Write(tmp / "case.toml", Config(tmp / "out", "[0.1, 0.0, 0.0]", "[bounds]\nlocked = [\"tx\"]\n"));
  const std::string log = (tmp / "watch.log").string();
  std::thread watcher([&] {
    const std::string cmd = std::string(OCCLUDE_BINARY) + " refine " +
                            (tmp / "case.toml").string() +
                            " --from-config --watch --max-refinements 2 > " + log + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
  });
  auto read_log = [&] {
    std::ifstream in(log);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  for (int i = 0; i < 600 && read_log().find("watching") == std::string::npos; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ASSERT_NE(read_log().find("watching"), std::string::npos) << read_log();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  Write(tmp / "case.toml",
        Config(tmp / "out", "[0.25, 0.0, 0.0]", "[bounds]\nlocked = [\"tx\"]\n"));
  watcher.join();
  const std::string out = read_log();
  EXPECT_NE(out.find("moved t (0.100,"), std::string::npos) << out;
  EXPECT_NE(out.find("moved t (0.250,"), std::string::npos)
      << out;  // from the same base, not cumulative
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

// Issue 8: the same inputs, seed and thread count give byte-identical pose.json and
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
  EXPECT_EQ(ReadText(tmp / "a" / "upper_at_pose.stl"), ReadText(tmp / "b" / "upper_at_pose.stl"));
  EXPECT_EQ(WithoutTimings(tmp / "a" / "metrics.json"), WithoutTimings(tmp / "b" / "metrics.json"));
  EXPECT_EQ(ReadText(tmp / "a" / "proposals" / "proposal-1.json"),
            ReadText(tmp / "b" / "proposals" / "proposal-1.json"));
}

// `occlude demo` (what scripts/demo runs): propose on the embedded synthetic case finds the
// designed bite, writes the report and the case config it ran, which `refine` then takes.
TEST(DemoCommandTest, ProposesTheDesignedBiteAndLeavesARefinableCase) {
  test::TempDir tmp;
  const test::CommandRun r =
      test::Occlude("demo --triangles 5000 --voxel 0.5 --out " + (tmp / "demo").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f :
       {"report.html", "metrics.json", "pose.json", "proposals.json", "case.toml"}) {
    EXPECT_TRUE(std::filesystem::exists(tmp / "demo" / f)) << f;
  }
  const Eigen::Isometry3d best = ReadPoseFile(tmp / "demo" / "pose.json");
  EXPECT_LT(TranslationNorm(best), kFoundMm) << best.matrix();
  EXPECT_NE(r.output.find("of the designed bite"), std::string::npos) << r.output;
  const test::CommandRun refine = test::Occlude("refine " + (tmp / "demo" / "case.toml").string());
  ASSERT_EQ(refine.exit_code, 0) << refine.output;
  EXPECT_TRUE(std::filesystem::exists(tmp / "demo" / "refine.json"));
}

// The memory guard of a session asks about other voxel sizes than the config's: over the
// budget at 0.2 mm, it names a coarser one that fits (the estimate follows the voxel size).
TEST(ProposeCommandTest, MemoryGuardNamesACoarserVoxelThatFits) {
  test::TempDir tmp;
  Write(tmp / "case.toml",
        "[synthetic]\ntriangles = 20000\n[output]\nfolder = \"" + (tmp / "out").string() + "\"\n");
  const test::CommandRun r =
      test::Occlude("propose " + (tmp / "case.toml").string() + " --memory-budget-mb 500");
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
