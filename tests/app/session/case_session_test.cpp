// CaseSession's oracles on the synthetic pair (5,000 triangles per jaw): none holds the
// structures only tree-pair queries read; ReleaseCoarseOracles frees the schedule but its
// finest oracle, which stays the same object, and a later Schedule() builds stages that answer
// as the first ones did.
#include "session/case_session.h"

#include <gtest/gtest.h>

#include <vector>

#include "config/case_config.h"
#include "occlude/io/content_hash.h"

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

}  // namespace
}  // namespace occlude::app
