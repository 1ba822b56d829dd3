// Line charts drawn with OpenCV (see chart.h).
#include "chart/chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "base/png_writer.h"

namespace occlude::app {
namespace {

// Tableau-like palette, BGR.
const cv::Scalar kPalette[] = {
    {180, 119, 31}, {14, 127, 255},  {44, 160, 44},   {40, 39, 214},  {189, 103, 148},
    {75, 86, 140},  {194, 119, 227}, {127, 127, 127}, {34, 189, 188}, {207, 190, 23},
};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);
const cv::Scalar kInk(40, 40, 40), kGrid(225, 225, 225), kWhite(255, 255, 255);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// One axis: data range mapped to pixels, with ticks.
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;  // in transformed units (log10 when log)
  double Transform(double v) const { return log ? std::log10(v) : v; }
  bool Drawable(double v) const { return std::isfinite(v) && (!log || v > 0.0); }
  double Fraction(double v) const { return (Transform(v) - lo) / (hi - lo); }
};

// Nice linear ticks (steps of 1, 2 or 5 times a power of ten).
std::vector<double> LinearTicks(double lo, double hi) {
  const double span = hi - lo;
  const double raw = span / 6.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (const double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step) * step; t <= hi + 1e-9 * span; t += step) {
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  }
  return ticks;
}

std::string FormatTick(double v) {
  char text[32];
  const double a = std::abs(v);
  if (a != 0.0 && (a >= 1e5 || a < 1e-3)) {
    std::snprintf(text, sizeof text, "%.0e", v);
  } else {
    std::snprintf(text, sizeof text, "%g", v);
  }
  return text;
}

void PutText(cv::Mat& img, const std::string& text, cv::Point at, double scale,
             const cv::Scalar& color, int thickness = 1) {
  cv::putText(img, text, at, kFont, scale, color, thickness, cv::LINE_AA);
}

cv::Size TextSize(const std::string& text, double scale, int thickness = 1) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, scale, thickness, &baseline);
}

void DashedLine(cv::Mat& img, cv::Point2d a, cv::Point2d b, const cv::Scalar& color,
                int thickness) {
  const double length = cv::norm(b - a);
  const double dash = 9.0, gap = 6.0;
  for (double s = 0.0; s < length; s += dash + gap) {
    const double e = std::min(length, s + dash);
    const cv::Point2d p = a + (b - a) * (s / length), q = a + (b - a) * (e / length);
    cv::line(img, p, q, color, thickness, cv::LINE_AA);
  }
}

}  // namespace

int ChartTextWidth(const std::string& text, double scale) { return TextSize(text, scale).width; }

std::vector<std::string> WrapChartText(const std::string& text, double scale, int max_width_px) {
  std::vector<std::string> lines;
  std::string line, word;
  std::istringstream words(text);
  while (words >> word) {
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && TextSize(longer, scale).width > max_width_px) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

namespace {

// The axes of a chart: the drawable data's range (with the references and y_include), padded;
// a log y axis snapped to whole decades.
struct ChartAxes {
  Axis x, y;
  bool categorical = false;
};

void Include(double v, double* lo, double* hi) {
  *lo = std::min(*lo, v);
  *hi = std::max(*hi, v);
}

ChartAxes DataRange(const LineChart& chart) {
  ChartAxes a;
  a.categorical = !chart.x_categories.empty();
  a.x.log = chart.log_x && !a.categorical;
  a.y.log = chart.log_y;
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
  double y_lo = x_lo, y_hi = -x_lo;
  std::size_t drawable = 0;
  for (const ChartSeries& s : chart.series) {
    for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!a.x.Drawable(s.x[i]) || !a.y.Drawable(s.y[i])) continue;
      Include(a.x.Transform(s.x[i]), &x_lo, &x_hi);
      Include(a.y.Transform(s.y[i]), &y_lo, &y_hi);
      ++drawable;
    }
  }
  if (drawable == 0) throw std::invalid_argument("chart '" + chart.title + "': no drawable point");
  for (const ChartReference& r : chart.references) {
    if (a.y.Drawable(r.y)) Include(a.y.Transform(r.y), &y_lo, &y_hi);
  }
  for (const double y : chart.y_include) {
    if (a.y.Drawable(y)) Include(a.y.Transform(y), &y_lo, &y_hi);
  }
  a.x.lo = x_lo, a.x.hi = x_hi, a.y.lo = y_lo, a.y.hi = y_hi;
  return a;
}

ChartAxes PaddedAxes(const LineChart& chart) {
  ChartAxes a = DataRange(chart);
  double &x_lo = a.x.lo, &x_hi = a.x.hi, &y_lo = a.y.lo, &y_hi = a.y.hi;
  if (a.categorical) {
    x_lo = -0.5;
    x_hi = static_cast<double>(chart.x_categories.size()) - 0.5;
  }
  if (a.y.log) {
    y_lo = std::floor(y_lo);
    y_hi = std::max(std::ceil(y_hi), y_lo + 1.0);
  } else {
    const double pad = y_hi > y_lo ? 0.05 * (y_hi - y_lo) : std::max(1.0, std::abs(y_hi)) * 0.1;
    y_lo -= pad;
    y_hi += pad;
  }
  if (a.x.log) {  // padded, not snapped to decades (points stay off the frame)
    const double span = std::max(x_hi - x_lo, 0.5), mid = 0.5 * (x_lo + x_hi);
    x_lo = std::min(x_lo, mid - 0.5 * span) - 0.06 * span;
    x_hi = std::max(x_hi, mid + 0.5 * span) + 0.06 * span;
  } else if (!a.categorical) {
    const double pad = x_hi > x_lo ? 0.03 * (x_hi - x_lo) : 1.0;
    x_lo -= pad;
    x_hi += pad;
  }
  return a;
}

// The plot area inside the image: margins for the tick labels, the legend (right) and the
// title with the subtitle's lines.
struct ChartLayout {
  static constexpr int kLeft = 95, kRight = 300, kBottom = 75;
  static constexpr double kSubtitleScale = 0.45;
  static constexpr int kSubtitleLine = 18;  // pixels per subtitle line
  std::vector<std::string> subtitle;
  int top = 60;
  cv::Rect plot;
  double Px(double fx) const { return plot.x + fx * plot.width; }
  double Py(double fy) const { return plot.y + (1.0 - fy) * plot.height; }
};

ChartLayout Layout(const LineChart& chart) {
  ChartLayout l;
  l.subtitle = WrapChartText(chart.subtitle, ChartLayout::kSubtitleScale,
                             chart.width - ChartLayout::kLeft - 20);
  l.top = l.subtitle.empty()
              ? 60
              : 62 + ChartLayout::kSubtitleLine * static_cast<int>(l.subtitle.size());
  l.plot =
      cv::Rect(ChartLayout::kLeft, l.top, chart.width - ChartLayout::kLeft - ChartLayout::kRight,
               chart.height - l.top - ChartLayout::kBottom);
  return l;
}

using Ticks = std::vector<std::pair<double, std::string>>;

// Tick positions (in the axis' transformed units) and labels.
Ticks YTicks(const Axis& ay) {
  Ticks ticks;
  if (ay.log) {
    for (double e = ay.lo; e <= ay.hi + 1e-9; e += 1.0)
      ticks.emplace_back(e, FormatTick(std::pow(10.0, e)));
  } else {
    for (const double t : LinearTicks(ay.lo, ay.hi)) ticks.emplace_back(t, FormatTick(t));
  }
  return ticks;
}

Ticks XTicks(const LineChart& chart, const ChartAxes& axes) {
  const Axis& ax = axes.x;
  Ticks ticks;
  if (axes.categorical) {
    for (std::size_t i = 0; i < chart.x_categories.size(); ++i) {
      ticks.emplace_back(static_cast<double>(i), chart.x_categories[i]);
    }
  } else if (ax.log) {
    // Decades, and 2x / 5x in between when fewer than three decades show.
    const bool fine = std::floor(ax.hi) - std::ceil(ax.lo) < 2.0;
    for (double e = std::floor(ax.lo); e <= ax.hi; e += 1.0) {
      for (const double m : {1.0, 2.0, 5.0}) {
        const double t = e + std::log10(m);
        if ((m == 1.0 || fine) && t >= ax.lo && t <= ax.hi)
          ticks.emplace_back(t, FormatTick(std::pow(10.0, t)));
      }
    }
  } else {
    for (const double t : LinearTicks(ax.lo, ax.hi)) ticks.emplace_back(t, FormatTick(t));
  }
  return ticks;
}

// Grid lines, tick labels, minor marks of log axes and the plot frame.
void DrawGrid(cv::Mat& img, const LineChart& chart, const ChartAxes& axes, const ChartLayout& l) {
  const Axis &ax = axes.x, &ay = axes.y;
  const cv::Rect& plot = l.plot;
  for (const auto& [t, label] : YTicks(ay)) {
    const double y = l.Py((t - ay.lo) / (ay.hi - ay.lo));
    cv::line(img, cv::Point2d(plot.x, y), cv::Point2d(plot.x + plot.width, y), kGrid, 1);
    if (ay.log && t + 1.0 <= ay.hi + 1e-9) {  // minor decade lines
      for (int m = 2; m <= 9; ++m) {
        const double ym = l.Py((t + std::log10(m) - ay.lo) / (ay.hi - ay.lo));
        cv::line(img, cv::Point2d(plot.x, ym), cv::Point2d(plot.x + 6, ym), kInk, 1);
      }
    }
    const cv::Size size = TextSize(label, 0.5);
    PutText(img, label, cv::Point(plot.x - 8 - size.width, static_cast<int>(y) + size.height / 2),
            0.5, kInk);
  }
  for (const auto& [t, label] : XTicks(chart, axes)) {
    const double x = l.Px((t - ax.lo) / (ax.hi - ax.lo));
    cv::line(img, cv::Point2d(x, plot.y), cv::Point2d(x, plot.y + plot.height), kGrid, 1);
    const cv::Size size = TextSize(label, 0.45);
    PutText(img, label, cv::Point(static_cast<int>(x) - size.width / 2, plot.y + plot.height + 20),
            0.45, kInk);
  }
  if (ax.log) {  // minor marks at 2..9 times each decade
    for (double e = std::floor(ax.lo); e <= ax.hi; e += 1.0) {
      for (int m = 2; m <= 9; ++m) {
        const double t = e + std::log10(m);
        if (t < ax.lo || t > ax.hi) continue;
        const double xm = l.Px((t - ax.lo) / (ax.hi - ax.lo));
        cv::line(img, cv::Point2d(xm, plot.y + plot.height),
                 cv::Point2d(xm, plot.y + plot.height - 6), kInk, 1);
      }
    }
  }
  cv::rectangle(img, plot, kInk, 1);
}

void DrawReferences(cv::Mat& img, const LineChart& chart, const Axis& ay, const ChartLayout& l) {
  for (const ChartReference& r : chart.references) {
    if (!ay.Drawable(r.y)) continue;
    const double y = l.Py(ay.Fraction(r.y));
    DashedLine(img, cv::Point2d(l.plot.x, y), cv::Point2d(l.plot.x + l.plot.width, y),
               cv::Scalar(0, 0, 170), 1);
    PutText(img, r.label, cv::Point(l.plot.x + 6, static_cast<int>(y) - 5), 0.45,
            cv::Scalar(0, 0, 170));
  }
}

cv::Scalar SeriesColour(const ChartSeries& s, std::size_t k) {
  return kPalette[(s.color >= 0 ? s.color : static_cast<int>(k)) % kPaletteSize];
}

// One series inside the plot area (clipped): lines (dashed or solid), markers, labels.
void DrawSeries(cv::Mat& clip, const ChartSeries& s, const cv::Scalar& color, const ChartAxes& axes,
                const ChartLayout& l) {
  bool have_prev = false;
  cv::Point2d prev;
  for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
    if (!axes.x.Drawable(s.x[i]) || !axes.y.Drawable(s.y[i])) {
      have_prev = false;
      continue;
    }
    const cv::Point2d p(l.Px(axes.x.Fraction(s.x[i])) - l.plot.x,
                        l.Py(axes.y.Fraction(s.y[i])) - l.plot.y);
    if (have_prev && !s.markers_only) {
      if (s.dashed) {
        DashedLine(clip, prev, p, color, 2);
      } else {
        cv::line(clip, prev, p, color, 2, cv::LINE_AA);
      }
    }
    if (s.dashed) {
      cv::rectangle(clip, p - cv::Point2d(3, 3), p + cv::Point2d(3, 3), color, cv::FILLED);
    } else {
      cv::circle(clip, p, 4, color, cv::FILLED, cv::LINE_AA);
    }
    if (i < s.labels.size() && !s.labels[i].empty()) {
      PutText(clip, s.labels[i], cv::Point(static_cast<int>(p.x) + 6, static_cast<int>(p.y) - 6),
              0.4, color);
    }
    prev = p;
    have_prev = true;
  }
}

// The title, the subtitle's lines and the axis labels (the y label rotated).
void DrawTitles(cv::Mat& img, const LineChart& chart, const ChartLayout& l) {
  const cv::Rect& plot = l.plot;
  PutText(img, chart.title, cv::Point(ChartLayout::kLeft, 30), 0.7, kInk, 2);
  for (std::size_t i = 0; i < l.subtitle.size(); ++i) {
    PutText(img, l.subtitle[i],
            cv::Point(ChartLayout::kLeft, 58 + ChartLayout::kSubtitleLine * static_cast<int>(i)),
            ChartLayout::kSubtitleScale, kInk);
  }
  const cv::Size xs = TextSize(chart.x_label, 0.55);
  PutText(img, chart.x_label, cv::Point(plot.x + (plot.width - xs.width) / 2, chart.height - 22),
          0.55, kInk);
  const cv::Size ys = TextSize(chart.y_label, 0.55);
  cv::Mat label(ys.height + 10, ys.width + 4, CV_8UC3, kWhite);
  PutText(label, chart.y_label, cv::Point(2, ys.height + 2), 0.55, kInk);
  cv::Mat rotated;
  cv::rotate(label, rotated, cv::ROTATE_90_COUNTERCLOCKWISE);
  const int x0 = 12, y0 = std::max(0, plot.y + (plot.height - rotated.rows) / 2);
  if (y0 + rotated.rows <= img.rows && x0 + rotated.cols <= img.cols) {
    rotated.copyTo(img(cv::Rect(x0, y0, rotated.cols, rotated.rows)));
  }
}

// The legend right of the plot: each series' line style and name.
void DrawLegend(cv::Mat& img, const LineChart& chart, const ChartLayout& l) {
  int ly = l.top + 12;
  const int lx = l.plot.x + l.plot.width + 18;
  for (std::size_t k = 0; k < chart.series.size(); ++k) {
    const ChartSeries& s = chart.series[k];
    const cv::Scalar color = SeriesColour(s, k);
    if (s.markers_only) {
      cv::circle(img, cv::Point(lx + 17, ly - 5), 4, color, cv::FILLED, cv::LINE_AA);
    } else if (s.dashed) {
      DashedLine(img, cv::Point2d(lx, ly - 5), cv::Point2d(lx + 34, ly - 5), color, 2);
    } else {
      cv::line(img, cv::Point(lx, ly - 5), cv::Point(lx + 34, ly - 5), color, 2, cv::LINE_AA);
    }
    PutText(img, s.name, cv::Point(lx + 42, ly), 0.45, kInk);
    ly += 22;
  }
}

}  // namespace

std::string RenderLineChartPng(const LineChart& chart) {
  const ChartAxes axes = PaddedAxes(chart);
  cv::Mat img(chart.height, chart.width, CV_8UC3, kWhite);
  const ChartLayout layout = Layout(chart);
  DrawGrid(img, chart, axes, layout);
  DrawReferences(img, chart, axes.y, layout);
  cv::Mat clip = img(layout.plot);
  for (std::size_t k = 0; k < chart.series.size(); ++k) {
    DrawSeries(clip, chart.series[k], SeriesColour(chart.series[k], k), axes, layout);
  }
  DrawTitles(img, chart, layout);
  DrawLegend(img, chart, layout);
  return EncodePng(img.data, img.cols, img.rows, PngPixels::kBgr, img.step);
}

}  // namespace occlude::app
