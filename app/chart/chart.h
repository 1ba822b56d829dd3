// Line charts for the benchmark and validation reports, drawn with OpenCV and
// returned as PNG bytes (write them with WriteFileAtomic). OpenCV stays inside
// occlude_app_lib: nothing here includes an OpenCV header.
#pragma once

#include <string>
#include <vector>

namespace occlude::app {

/// One line of a chart. Points with a non-finite or (on a log axis) non-positive
/// coordinate are skipped, and the line is broken there.
struct ChartSeries {
  std::string name;
  std::vector<double> x, y;
  int color = -1;             ///< index into the chart palette; -1 = the series' position
  bool dashed = false;        ///< e.g. the peer library's lines
  bool markers_only = false;  ///< points without connecting lines (a scatter)
  std::vector<std::string> labels = {};  ///< optional text beside each point (index as x, y)
};

/// A horizontal reference line (a deadline, a target).
struct ChartReference {
  double y = 0.0;
  std::string label;
};

struct LineChart {
  std::string title;
  std::string subtitle;  ///< second title line (machine, settings), smaller
  std::string x_label, y_label;
  bool log_x = false, log_y = false;
  /// Categorical x: when non-empty, x values are indices into these labels,
  /// drawn evenly spaced (for sweeps whose offsets crowd near contact).
  std::vector<std::string> x_categories;
  std::vector<ChartSeries> series;
  std::vector<ChartReference> references;
  /// Values the y axis spans whatever the data (0 and 100 for a percentage).
  std::vector<double> y_include;
  int width = 1100, height = 700;
};

/// Width in pixels of `text` in the charts' font at `scale`.
int ChartTextWidth(const std::string& text, double scale);
/// `text` in lines no wider than max_width_px at `scale`, broken at spaces (a word wider
/// than that stays whole on its own line): how a chart's subtitle fits its width.
std::vector<std::string> WrapChartText(const std::string& text, double scale, int max_width_px);

/// Renders the chart as a PNG file's bytes. Throws std::invalid_argument when
/// no series has a drawable point.
std::string RenderLineChartPng(const LineChart& chart);

}  // namespace occlude::app
