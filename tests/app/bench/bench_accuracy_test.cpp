// The Pareto marking of `occlude bench --accuracy`: exactly the rows no other row beats in
// time and p95 error among those that find the contacts. (The command's outputs:
// tests/app/cli/cmd_bench_test.cpp.)
#include "bench/bench_accuracy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace occlude::test {
namespace {

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

}  // namespace
}  // namespace occlude::test
