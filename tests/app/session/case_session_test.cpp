// CaseSession's oracles on the synthetic pair (5,000 triangles per jaw): none holds the
// structures only tree-pair queries read; ReleaseCoarseOracles frees the schedule but its
// finest oracle, which stays the same object, and a later Schedule() builds stages that answer
// as the first ones did; what Prefetch() starts equals what is made on demand.
#include "session/case_session.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <vector>

#include "config/case_config.h"
#include "occlude/io/content_hash.h"
#include "test_common.h"

namespace occlude::app {
namespace {

// The hash of the oracle's sub-voxel answers at poses about the bite (pushed in, at it, opened).
std::uint64_t AnswersDigest(const collision::JawOracle& oracle) {
  io::Hasher64 hash;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Isometry3d X(Eigen::Translation3d(0.0, -0.2 + 0.1 * i, 0.0));
    collision::OracleResult result;
    oracle.Query(X, collision::OracleRequest{}, &result);
    collision::HashOracleResult(result, &hash);
  }
  return hash.Finish();
}

TEST(CaseSessionTest, CoarseOraclesAreReleasedAndBuiltAgainAlike) {
  CaseConfig config =
      ParseCaseConfig("[synthetic]\ntriangles = 5000\nseed = 1\n", "synthetic.toml");
  config.cache_enabled = false;  // every stage built here, again after the release
  CaseSession session(config);
  const planner::OracleSchedule first = session.Schedule();
  ASSERT_EQ(first.size(), 3u);  // 0.8, 0.4 and 0.2 mm
  std::vector<std::uint64_t> digests;
  for (const planner::OracleStage& stage : first) {
    EXPECT_TRUE(stage.oracle->lower_tree().explicit_spheres().empty());
    EXPECT_TRUE(stage.oracle->upper_tree().explicit_spheres().empty());
    digests.push_back(AnswersDigest(*stage.oracle));
  }
  const collision::JawOracle* finest = first.back().oracle;
  session.ReleaseCoarseOracles();
  EXPECT_EQ(&session.FinestOracle(), finest);
  const planner::OracleSchedule& again = session.Schedule();
  ASSERT_EQ(again.size(), first.size());
  EXPECT_EQ(again.back().oracle, finest);
  for (std::size_t i = 0; i < again.size(); ++i) {
    EXPECT_EQ(again[i].level, first[i].level) << "stage " << i;
    EXPECT_EQ(AnswersDigest(*again[i].oracle), digests[i]) << "stage " << i;
  }
}

// A schedule read from a warm cache (the stages it holds read at once, the one missing built)
// is the cold schedule: every stage answers alike, and the models are listed in stage order;
// BuiltOracles tells a session that built one from one that read them all.
TEST(CaseSessionTest, ScheduleReadFromTheCacheAnswersAsBuilt) {
  const test::TempDir dir;
  CaseConfig config =
      ParseCaseConfig("[synthetic]\ntriangles = 5000\nseed = 1\n", "synthetic.toml");
  config.cache_folder = dir.path();
  std::vector<std::uint64_t> digests;
  std::vector<double> voxels;
  {
    CaseSession cold(config);
    EXPECT_FALSE(cold.BuiltOracles());
    for (const planner::OracleStage& stage : cold.Schedule())
      digests.push_back(AnswersDigest(*stage.oracle));
    EXPECT_TRUE(cold.BuiltOracles());
    for (const OracleModel& m : cold.Models()) voxels.push_back(m.voxel_mm);
  }
  ASSERT_EQ(digests.size(), 3u);
  ASSERT_EQ(voxels, (std::vector<double>{0.8, 0.4, 0.2}));
  std::vector<std::filesystem::path> entries;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    if (e.path().filename().string().rfind("oracle-", 0) == 0) entries.push_back(e.path());
  }
  ASSERT_EQ(entries.size(), 3u);
  std::sort(entries.begin(), entries.end());
  for (const bool drop_one : {false, true}) {
    if (drop_one) std::filesystem::remove(entries[1]);  // one stage to build again
    CaseSession warm(config);
    const planner::OracleSchedule& schedule = warm.Schedule();
    ASSERT_EQ(schedule.size(), digests.size());
    for (std::size_t i = 0; i < schedule.size(); ++i)
      EXPECT_EQ(AnswersDigest(*schedule[i].oracle), digests[i])
          << "stage " << i << (drop_one ? ", one stage rebuilt" : "");
    std::vector<double> warm_voxels;
    for (const OracleModel& m : warm.Models()) warm_voxels.push_back(m.voxel_mm);
    EXPECT_EQ(warm_voxels, voxels) << drop_one;
    EXPECT_EQ(warm.BuiltOracles(), drop_one);  // read alone, or one stage built
  }
}

// The same session's arch analysis and map fields, prefetched on threads of their own or made
// when first asked for, answer alike; a session moved while its prefetch runs keeps it.
TEST(CaseSessionTest, PrefetchedAnalysisAndMapsEqualThoseMadeOnDemand) {
  CaseConfig config =
      ParseCaseConfig("[synthetic]\ntriangles = 5000\nseed = 1\n", "synthetic.toml");
  config.cache_enabled = false;
  CaseSession on_demand(config);
  auto moved = std::make_unique<CaseSession>(config);
  moved->Prefetch();
  moved->Prefetch();  // under way: nothing more
  CaseSession prefetched = std::move(*moved);
  moved.reset();
  const Eigen::Isometry3d X_LU(Eigen::Translation3d(0.1, -0.05, 0.2));
  const analysis::Relationships a = RelationshipsAt(on_demand.Analysis(), X_LU);
  const analysis::Relationships b = RelationshipsAt(prefetched.Analysis(), X_LU);
  ASSERT_TRUE(a.overjet.mm && a.overbite.mm && a.midline_deviation.mm && a.molar[0].offset.mm);
  EXPECT_EQ(a.overjet.mm, b.overjet.mm);
  EXPECT_EQ(a.overbite.mm, b.overbite.mm);
  EXPECT_EQ(a.midline_deviation.mm, b.midline_deviation.mm);
  EXPECT_EQ(a.molar[0].offset.mm, b.molar[0].offset.mm);
  ASSERT_EQ(on_demand.Analysis().upper_U.landmarks.size(),
            prefetched.Analysis().upper_U.landmarks.size());
  // Points about the jaws' surfaces (their vertices, moved a little).
  const auto& jaws = prefetched.jaws();
  int answered = 0;
  for (std::size_t i = 0; i < jaws.upper_U->vertices.size(); i += 97) {
    const Eigen::Vector3d p = jaws.upper_U->vertices[i] + Eigen::Vector3d(0.1, 0.2, -0.1);
    const Eigen::Vector3d q = jaws.lower_L->vertices[i] + Eigen::Vector3d(0.1, 0.2, -0.1);
    collision::SignedDistanceSample x, y;
    ASSERT_EQ(on_demand.Maps().upper().Exact(p, 1.0, &x),
              prefetched.Maps().upper().Exact(p, 1.0, &y));
    EXPECT_EQ(x.distance, y.distance);
    ASSERT_EQ(on_demand.Maps().lower().Exact(q, 1.0, &x),
              prefetched.Maps().lower().Exact(q, 1.0, &y));
    EXPECT_EQ(x.distance, y.distance);
    ++answered;
  }
  EXPECT_GT(answered, 20);
  prefetched.Prefetch();  // done: nothing to start
}

}  // namespace
}  // namespace occlude::app
