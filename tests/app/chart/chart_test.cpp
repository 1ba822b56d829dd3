// Line charts: long subtitles wrap at spaces within the width (nothing lost, words whole), a
// chart renders as a PNG of the requested size, and a chart with no drawable point is refused.
#include "chart/chart.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "bench_files.h"

namespace occlude::test {
namespace {

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
