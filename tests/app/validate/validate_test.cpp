// `occlude validate` on the smallest synthetic pair: the magnitudes parser, one run per
// solver, magnitude and start with the documented columns, the closing rows start at the
// reference, easy perturbations return within the success bar, the consensus statistics,
// the charts. (The command: tests/app/cli/cmd_validate_test.cpp.)
#include "validate/validate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "base/user_error.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::app {
namespace {

TEST(ValidateTest, ParsesMagnitudesAndRejectsBadText) {
  const auto m = ParseMagnitudes("1:2,2:3,5:10,0:0");
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[2].mm, 5.0);
  EXPECT_EQ(m[2].deg, 10.0);
  for (const char* bad : {"", "1-2", "1:", ":2", "a:b", "1:2,", "-1:2", "1:90", "1:2x"}) {
    try {
      ParseMagnitudes(bad);
      if (std::string(bad) != "1:2,") ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const UserError& e) {
      EXPECT_NE(std::string(e.what()).find("--magnitudes"), std::string::npos) << e.what();
    }
  }
}

const ValidateResult& SmallRun(ValidateOptions* used = nullptr) {
  static ValidateOptions options = [] {
    ValidateOptions o;
    o.solvers = {planner::SolverKind::kCeres, planner::SolverKind::kCoarseToFine};
#ifdef OCCLUDE_SANITIZED
    o.starts = 2;  // the sanitizer lane looks for memory errors, not statistics
#else
    o.starts = 3;
#endif
    o.magnitudes = {{0.0, 0.0}, {0.5, 1.0}};
    o.voxels_mm = {0.8, 0.5};
    o.threads = 2;
    o.solver_starts = 2;
    o.global_samples = 6;
    return o;
  }();
  static const ValidateResult result =
      RunValidation(SyntheticJawPair(io::kMinSyntheticTriangles, 1), options);
  if (used) *used = options;
  return result;
}

void CheckRunsAndSummaries(const ValidateResult& r, const ValidateOptions& options) {
  ASSERT_EQ(r.runs.size(), 2u * 2u * static_cast<std::size_t>(options.starts));
  for (const ValidateRun& run : r.runs) {
    const bool closing = run.magnitude.mm == 0.0;
    if (closing) {
      EXPECT_NEAR(run.start_error.translation_mm, 0.0, 1e-9);
      EXPECT_NEAR(run.start_error.rotation_deg, 0.0, 1e-9);
    } else {
      // The perturbation lies in the ball; the reference points sit within ~35 mm of the
      // pivot, so 1 degree moves them by at most 0.6 mm more.
      EXPECT_LE(run.start_error.rotation_deg, 1.0 + 1e-9);
      EXPECT_LE(run.start_error.translation_mm, 0.5 + 0.61);
    }
    EXPECT_TRUE(run.success) << planner::ToString(run.solver) << " magnitude " << run.magnitude.mm
                             << " start " << run.start << ": " << run.error.translation_mm << " mm "
                             << run.error.rotation_deg << " deg";
    EXPECT_LE(run.constrained_penetration_mm, options.max_penetration_mm + 0.004);
    EXPECT_GT(run.seconds, 0.0);
    EXPECT_TRUE(run.X_LU.matrix().allFinite());
  }
  ASSERT_EQ(r.summary.size(), 4u);
  for (const ValidateSummary& s : r.summary) {
    EXPECT_EQ(s.runs, options.starts);
    EXPECT_DOUBLE_EQ(s.success_rate, 1.0);
    EXPECT_LE(s.median_err_mm, s.p95_err_mm);
    EXPECT_LE(s.median_consensus_mm, options.success_mm);
    EXPECT_DOUBLE_EQ(s.within_consensus, 1.0);
  }
}

void CheckCsvAndCharts(const ValidateResult& r, const ValidateOptions& options) {
  std::istringstream csv(ValidateCsv(r));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(
      header.rfind("solver,magnitude_mm,magnitude_deg,start,err_mm,err_deg,max_penetration_mm,"
                   "contact_area_mm2,seconds,success",
                   0),
      0u)
      << header;
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, static_cast<int>(r.runs.size()));
  EXPECT_NE(
      ValidateSummaryCsv(r).find("coarse-to-fine,0.5,1," + std::to_string(options.starts) + ",1,"),
      std::string::npos)
      << ValidateSummaryCsv(r);
  const std::string text = ValidateSummaryText(r, options, "test machine");
  EXPECT_NE(text.find("closing"), std::string::npos);
  EXPECT_NE(text.find("reference pose as given"), std::string::npos);
  const auto charts = ValidateCharts(r, options, "test");
  ASSERT_EQ(charts.size(), 4u);
  EXPECT_EQ(charts.back().first, "reference-path.png");
  for (const auto& [file, png] : charts) {
    ASSERT_GT(png.size(), 8u) << file;
    EXPECT_EQ(png.substr(1, 3), "PNG") << file;
  }
}

// The reference check on a reference the runs agree with: its path starts at the reference
// (same evaluation as `reference`) and ends at a consensus within the success bar.
void CheckReferencePath(const ValidateResult& r, const ValidateOptions& options) {
  const ReferenceCheck& c = r.reference_check;
  ASSERT_EQ(c.path.size(), static_cast<std::size_t>(options.path_steps) + 1);
  EXPECT_DOUBLE_EQ(c.path.front().s, 0.0);
  EXPECT_DOUBLE_EQ(c.path.back().s, 1.0);
  EXPECT_NEAR(c.path.front().from_start.translation_mm, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(c.path.front().evaluation.contact_area_mm2, r.reference.contact_area_mm2);
  EXPECT_LE(c.consensus_error.translation_mm, options.success_mm);
  EXPECT_TRUE(c.path.back().X_LU.isApprox(c.X_LU_consensus, 1e-12));
  for (std::size_t k = 1; k < c.path.size(); ++k) {  // monotone along a straight path
    EXPECT_GE(c.path[k].from_start.translation_mm, c.path[k - 1].from_start.translation_mm - 1e-9);
  }
  std::istringstream csv(ReferencePathCsv(r));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("s,from_reference_mm,from_reference_deg,contact_area_mm2", 0), 0u)
      << header;
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, options.path_steps + 1);
  EXPECT_NE(ValidateSummaryText(r, options, "m").find("reference check"), std::string::npos);
}

// One test for both checks: each ctest test is a process of its own, and the run is the
// cost (about 75 s each under the sanitizers).
TEST(ValidateTest, OneRunPerSolverMagnitudeAndStartWithTheirErrorsCsvAndCharts) {
  ValidateOptions options;
  const ValidateResult& r = SmallRun(&options);
  CheckRunsAndSummaries(r, options);
  CheckCsvAndCharts(r, options);
  CheckReferencePath(r, options);
}

TEST(PoseDominanceTest, MoreContactAndNoDeeperPenetrationDominates) {
  planner::PoseEvaluation a, b;
  a.contact_area_mm2 = 10.0;
  b.contact_area_mm2 = 8.0;
  a.constrained_penetration_mm = b.constrained_penetration_mm = 0.03;
  EXPECT_TRUE(planner::Dominates(a, b));
  EXPECT_FALSE(planner::Dominates(b, a));
  EXPECT_FALSE(planner::Dominates(a, a));  // strictly more contact
  a.constrained_penetration_mm = 0.031;
  EXPECT_FALSE(planner::Dominates(a, b));
  a.constrained_penetration_mm = 0.0;
  a.deep_samples = 1;
  EXPECT_FALSE(planner::Dominates(a, b));
}

// A "registered" bite that is not seated (the synthetic pair opened 0.5 mm along its occlusal
// axis, as the open-bite scan is; its jaws are then >= 0.38 mm apart): the closing runs find
// the designed bite, and the check must find poses on the way, beyond the 0.3 mm success bar,
// that dominate the opened reference (contact, no penetration).
TEST(ValidateTest, ReferenceCheckFindsAnUnseatedReferenceDominated) {
  JawPair jaws = SyntheticJawPair(io::kMinSyntheticTriangles, 1);
  const Eigen::Isometry3d X_bite = jaws.X_LU_ref;
  jaws.X_LU_ref.pretranslate(
      Eigen::Vector3d(0.0, 0.5, 0.0));  // +y: occlusal axis of the synthetic pair
  ValidateOptions o;
  o.solvers = {planner::SolverKind::kCeres};
  o.starts = 1;
  o.magnitudes = {{0.0, 0.0}};
  o.voxels_mm = {0.8, 0.5};
  o.threads = 1;
  const ValidateResult r = RunValidation(jaws, o);
  const ReferenceCheck& c = r.reference_check;
  EXPECT_EQ(r.reference.contact_area_mm2, 0.0);
  ASSERT_GE(c.nearest_dominating, 1);
  ASSERT_GE(c.nearest_dominating_beyond_bar, c.nearest_dominating);
  EXPECT_GT(
      c.path[static_cast<std::size_t>(c.nearest_dominating_beyond_bar)].from_start.translation_mm,
      o.success_mm);
  ASSERT_GE(c.most_contact_dominating, c.nearest_dominating);
  const planner::PoseEvaluation& best =
      c.path[static_cast<std::size_t>(c.most_contact_dominating)].evaluation;
  EXPECT_GT(best.contact_area_mm2, r.reference.contact_area_mm2 + 1.0);
  EXPECT_LE(best.constrained_penetration_mm, r.reference.constrained_penetration_mm);
  // The consensus is the designed bite again, 0.5 mm from the opened reference.
  EXPECT_NEAR(c.consensus_error.translation_mm, 0.5, 0.15);
  EXPECT_LT((c.X_LU_consensus.translation() - X_bite.translation()).norm(), 0.15);
  const std::string text = ValidateSummaryText(r, o, "m");
  EXPECT_NE(text.find("DOMINATED"), std::string::npos) << text;
}

}  // namespace
}  // namespace occlude::app
