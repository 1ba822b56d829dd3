// `occlude refine` through the real binary: it applies [adjust] with a locked degree of
// freedom and says what changed; --watch refines again on every save of the config, and shows
// new meshes after a save that changes them.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "bench_files.h"
#include "case_run.h"
#include "config/pose_file.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::app {
namespace {

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
  EXPECT_NE(r.output.find("  clinical: overjet: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("  clinical: molar relationship, right: "), std::string::npos)
      << r.output;
  const json refine = ReadJson(tmp / "out" / "refine.json");
  EXPECT_NEAR(refine["moved_from_base"]["translation_mm"][0].get<double>(), 0.3,
              1e-6);  // locked at the adjustment
  EXPECT_TRUE(refine["after"]["feasible"].get<bool>());
  const Eigen::Isometry3d after = ReadPoseFile(tmp / "out" / "pose.json");
  EXPECT_GT((after.translation() - base.translation()).norm(), 0.29);
}

// `occlude refine CASE --from-config --watch --max-refinements 2` on a thread of its own, its
// output in a log: Save() writes the config once the watch runs and waits for the command to end.
class WatchRun {
 public:
  explicit WatchRun(const std::filesystem::path& dir)
      : config_(dir / "case.toml"), log_(dir / "watch.log") {
    watcher_ = std::thread([this] {
      const std::string cmd = std::string(OCCLUDE_BINARY) + " refine " + config_.string() +
                              " --from-config --watch --max-refinements 2 > " + log_.string() +
                              " 2>&1";
      EXPECT_EQ(std::system(cmd.c_str()), 0);
    });
    for (int i = 0; i < 600 && !Watching(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ~WatchRun() {
    if (watcher_.joinable()) watcher_.join();
  }
  WatchRun(const WatchRun&) = delete;
  WatchRun& operator=(const WatchRun&) = delete;

  bool Watching() const { return Log().find("watching") != std::string::npos; }
  std::string Log() const { return test::ReadFileText(log_); }
  /// Saves `text` as the config (after a pause: a new time stamp) and waits for the second
  /// refinement.
  void Save(const std::string& text) {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    Write(config_, text);
    watcher_.join();
  }

 private:
  std::filesystem::path config_, log_;
  std::thread watcher_;
};

TEST(RefineCommandTest, WatchRefinesAgainOnEverySave) {
  test::TempDir tmp;
  Write(tmp / "case.toml", Config(tmp / "out", "[0.1, 0.0, 0.0]", "[bounds]\nlocked = [\"tx\"]\n"));
  WatchRun watch(tmp.path());
  ASSERT_TRUE(watch.Watching()) << watch.Log();
  watch.Save(Config(tmp / "out", "[0.25, 0.0, 0.0]", "[bounds]\nlocked = [\"tx\"]\n"));
  const std::string out = watch.Log();
  EXPECT_NE(out.find("moved t (0.100,"), std::string::npos) << out;
  EXPECT_NE(out.find("moved t (0.250,"), std::string::npos)
      << out;  // from the same base, not cumulative
}

// The 3D view's triangle counts in report.html ("triangles": lower's, then upper's).
std::vector<long> ViewTriangles(const std::filesystem::path& report) {
  const std::string html = test::ReadFileText(report);
  std::vector<long> counts;
  const std::string key = "\"triangles\":";
  for (std::size_t at = html.find(key); at != std::string::npos; at = html.find(key, at + 1))
    counts.push_back(std::stol(html.substr(at + key.size(), 12)));
  return counts;
}

// A save that changes the meshes makes a new session, and the next report's 3D view shows the
// new meshes (the watch keeps display meshes only while its session lives).
TEST(RefineCommandTest, WatchShowsTheNewMeshesAfterASaveChangesThem) {
  test::TempDir tmp;
  const std::string config = Config(tmp / "out", "[0.1, 0.0, 0.0]");
  Write(tmp / "case.toml", config);
  WatchRun watch(tmp.path());
  ASSERT_TRUE(watch.Watching()) << watch.Log();
  const std::vector<long> before = ViewTriangles(tmp / "out" / "report.html");
  std::string finer = config;
  finer.replace(finer.find("triangles = 5000"), 16, "triangles = 6000");
  watch.Save(finer);
  EXPECT_NE(watch.Log().find("rebuilding the models"), std::string::npos) << watch.Log();
  const json metrics = ReadJson(tmp / "out" / "metrics.json");
  const std::vector<long> after = ViewTriangles(tmp / "out" / "report.html");
  ASSERT_EQ(before.size(), 2u);
  ASSERT_EQ(after.size(), 2u);
  EXPECT_EQ(after[0], metrics["meshes"]["lower_triangles"].get<long>());
  EXPECT_EQ(after[1], metrics["meshes"]["upper_triangles"].get<long>());
  EXPECT_GT(after[0], before[0]);
  EXPECT_GT(after[1], before[1]);
}

// The example: from the synthetic bite, [adjust] moves 0.3 mm along x. By default
// refine holds tx at the adjusted value while the others settle; with refine.hold = "none"
// the seat pulls the jaw back; holding ty at a pose pushed 0.5 mm into the lower jaw cannot
// be made feasible, and the summary says by how much.
std::string HoldConfig(const std::filesystem::path& out, const std::string& adjust,
                       const std::string& hold) {
  return "[synthetic]\ntriangles = 5000\n[accuracy]\nvoxel_mm = 1.0\n[report]\n"
         "image_width_px = 300\n[adjust]\ntranslation_mm = " +
         adjust + "\n" + hold + "[output]\nfolder = \"" + out.string() + "\"\n";
}

// The jaw's slide back along x with hold = "none" is at least this (the seat pulls it home).
constexpr double kSlidBackMm = 0.15;

TEST(RefineCommandTest, HoldKeepsTheAdjustedDofUnlessNone) {
  test::TempDir tmp;
  const std::string refine = "refine " + (tmp / "case.toml").string() + " --from-config";
  Write(tmp / "case.toml", HoldConfig(tmp / "out", "[0.3, 0.0, 0.0]", ""));
  test::CommandRun r = test::Occlude(refine);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("held tx at the adjusted value (refine.hold = adjusted"),
            std::string::npos)
      << r.output;
  json out = ReadJson(tmp / "out" / "refine.json");
  EXPECT_NEAR(out["moved_from_base"]["translation_mm"][0].get<double>(), 0.3, 0.01);
  EXPECT_EQ(out["hold"]["held"], "tx");
  EXPECT_TRUE(out["after"]["feasible"].get<bool>());

  Write(tmp / "case.toml",
        HoldConfig(tmp / "out", "[0.3, 0.0, 0.0]", "[refine]\nhold = \"none\"\n"));
  r = test::Occlude(refine);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("held nothing"), std::string::npos) << r.output;
  out = ReadJson(tmp / "out" / "refine.json");
  EXPECT_LT(out["moved_from_base"]["translation_mm"][0].get<double>(), 0.3 - kSlidBackMm);

  Write(tmp / "case.toml",
        HoldConfig(tmp / "out", "[0.0, -0.5, 0.0]", "[refine]\nhold = [\"ty\"]\n"));
  r = test::Occlude(refine);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cannot be made feasible with ty held: penetration"), std::string::npos)
      << r.output;
  out = ReadJson(tmp / "out" / "refine.json");
  EXPECT_NEAR(out["moved_from_base"]["translation_mm"][1].get<double>(), -0.5, 0.01);
  EXPECT_GT(out["hold"]["penetration_over_limit_mm"].get<double>(), 0.1);
}

}  // namespace
}  // namespace occlude::app
