// Outputs of `occlude bench --accuracy` (see bench_accuracy.h): the CSV with
// its definitions in '#' lines, the JSON table for the planner, and the
// time-against-error charts with the Pareto front.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/text_format.h"
#include "bench/bench_accuracy.h"
#include "bench/bench_accuracy_score_internal.h"
#include "chart/chart.h"

namespace occlude::app {
namespace {

std::string Fraction(std::size_t part, std::size_t whole) {
  return whole == 0 ? std::string()
                    : FixedOrEmpty(static_cast<double>(part) / static_cast<double>(whole), 5);
}

std::string VoxelLabel(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// Errors below this are drawn on it (a log axis has no zero).
constexpr double kErrorFloorMm = 1e-5;

}  // namespace

std::string AccuracyCsv(const std::vector<AccuracyRow>& rows, const std::string& about) {
  std::ostringstream csv;
  std::istringstream lines(about);
  for (std::string line; std::getline(lines, line);) csv << "# " << line << "\n";
  csv << "# Ground truth: d*(p) = exact signed distance from a point p of the upper surface to the "
         "lower jaw's triangles (closest point over all triangles, sign from the angle-weighted "
         "pseudo-normal; > 0 outside). Fixed upper samples: each upper triangle split into k^2 "
         "pieces (k = ceil(longest edge / truth spacing)), their centroids, plus every vertex.\n"
         "# Truth contact: a sample with d* <= delta (touching or interpenetrating); true depth = "
         "max(0, -min d*) over the samples (measured to "
      << kDepthLimitMm
      << " mm deep).\n"
         "# Claims: every contact or penetration a method reports is a claim. Point claim (p, d): "
         "error |d - d*(p)|, false when d*(p) > delta (oracle points; exact pairs: each upper "
         "triangle's closest point and unsigned distance; FCL distance: its nearest point). Region "
         "claim (an upper voxel for IST voxel pairs, band delta; an upper triangle for FCL "
         "intersecting pairs, band 0): D = min d* over the element's samples, error max(0, D - h - "
         "band) with h the truth spacing (d* is 1-Lipschitz: the element's true minimum is at "
         "least D - h), false when D - h > delta, unscored when the element holds no sample.\n"
         "# Missed: truth contacts that no claim covers (a point claim within the sample spacing, "
         "for the oracle's sub-voxel and exact levels; a claim in the same upper voxel, for the "
         "oracle's voxel level and IST voxel pairs; a claim on the same upper triangle, for exact "
         "pairs and FCL all-contacts). Distance queries list no contacts: missed/false empty.\n"
         "# Errors (median/p95/max) pool every scored claim of every pose; pen_err = |stated "
         "depth - true depth| per pose (oracle only); *_half_band: truth contacts with |d*| <= "
         "delta/2 (touching within half the band, either side); "
         "false_double_band: truth > 2 delta. Times: thread CPU per query, every pose x reps.\n"
         "# pareto: on the front of (median_us, p95_err_mm) among the rows missing at most 1% of "
         "the truth contacts within delta/2.\n";
  csv << "method,variant,voxel_mm,level,median_us,p95_err_mm,max_err_mm,missed,false_contacts,"
         "query,p95_us,max_us,median_err_mm,claims,unscored,truth_contacts,missed_frac,"
         "truth_half_band,missed_half_band,false_frac,false_double_band,pen_err_median_mm,"
         "pen_err_max_mm,poses,build_s,bytes,pareto\n";
  for (const AccuracyRow& r : rows) {
    const bool c = r.contacts_defined;
    auto count = [&](std::size_t v) { return c ? std::to_string(v) : std::string(); };
    csv << r.method << ',' << r.variant << ',' << FixedOrEmpty(r.voxel_mm, 3) << ',' << r.level
        << ',' << FixedOrEmpty(r.us.median, 2) << ',' << FixedOrEmpty(r.p95_err_mm, 6) << ','
        << FixedOrEmpty(r.max_err_mm, 6) << ',' << count(r.missed) << ',' << count(r.false_contacts)
        << ',' << r.query << ',' << FixedOrEmpty(r.p95_us, 2) << ',' << FixedOrEmpty(r.us.max, 2)
        << ',' << FixedOrEmpty(r.median_err_mm, 6) << ',' << r.claims << ',' << r.unscored << ','
        << count(r.truth_contacts) << ',' << (c ? Fraction(r.missed, r.truth_contacts) : "") << ','
        << count(r.truth_half) << ',' << count(r.missed_half) << ','
        << (c ? Fraction(r.false_contacts, r.claims) : "") << ',' << count(r.false_double) << ','
        << FixedOrEmpty(r.pen_err_median_mm, 6) << ',' << FixedOrEmpty(r.pen_err_max_mm, 6) << ','
        << r.poses << ',' << FixedOrEmpty(r.build_s, 3) << ',' << r.bytes << ','
        << (r.pareto ? 1 : 0) << '\n';
  }
  return csv.str();
}

std::string AccuracyTableJson(const std::vector<AccuracyRow>& rows, const std::string& case_name,
                              const std::string& machine, const AccuracyOptions& options) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  auto entry = [&](const AccuracyRow& r) {
    nlohmann::json e;
    e["method"] = r.method;
    e["variant"] = r.variant;
    e["query"] = r.query;
    e["level"] = r.level;
    e["voxel_mm"] = number(r.voxel_mm);
    e["p95_err_mm"] = number(r.p95_err_mm);
    e["max_err_mm"] = number(r.max_err_mm);
    e["median_err_mm"] = number(r.median_err_mm);
    e["median_us"] = number(r.us.median);
    e["p95_us"] = number(r.p95_us);
    if (r.contacts_defined) {
      e["missed_frac"] = r.truth_contacts ? nlohmann::json(static_cast<double>(r.missed) /
                                                           static_cast<double>(r.truth_contacts))
                                          : nlohmann::json();
      e["missed_half_band"] = r.missed_half;
      e["false_frac"] = r.claims ? nlohmann::json(static_cast<double>(r.false_contacts) /
                                                  static_cast<double>(r.claims))
                                 : nlohmann::json();
    }
    e["pen_err_max_mm"] = number(r.pen_err_max_mm);
    e["build_s"] = r.build_s;
    e["bytes"] = r.bytes;
    e["pareto"] = r.pareto;
    return e;
  };
  std::vector<const AccuracyRow*> oracle;
  for (const AccuracyRow& r : rows) {
    if (r.query == "oracle") oracle.push_back(&r);
  }
  std::sort(oracle.begin(), oracle.end(),
            [](const AccuracyRow* a, const AccuracyRow* b) { return a->us.median < b->us.median; });
  nlohmann::json j;
  j["case"] = case_name;
  j["machine"] = machine;
  j["delta_mm"] = options.delta_mm;
  j["poses"] = options.poses;
  j["offset_range_mm"] = {options.offset_lo_mm, options.offset_hi_mm};
  j["truth_spacing_mm"] = options.truth_spacing_mm;
  j["pick"] =
      "oracle entries sorted by median_us: take the first whose p95_err_mm (and max_err_mm, "
      "missed_half_band if required) meets the wanted accuracy";
  j["oracle"] = nlohmann::json::array();
  for (const AccuracyRow* r : oracle) j["oracle"].push_back(entry(*r));
  j["all"] = nlohmann::json::array();
  for (const AccuracyRow& r : rows) j["all"].push_back(entry(r));
  return j.dump(2) + "\n";
}

namespace {

// A method's series on the accuracy charts: its name, colour and line style.
std::string SeriesName(const AccuracyRow& r) {
  if (r.method == "fcl") return "FCL " + r.query + (r.query == "distance" ? " (OBBRSS)" : "");
  if (r.query == "oracle") return "IST oracle, " + r.level + " level";
  return "IST pairs " + r.variant + (r.level == "exact" ? " + exact" : ", voxel");
}

ChartSeries NewSeries(const AccuracyRow& r) {
  ChartSeries s;
  s.name = SeriesName(r);
  if (r.method == "fcl") {
    s.color = r.query == "distance" ? 8 : 6;
    s.markers_only = true;
  } else if (r.query == "oracle") {
    s.color = r.level == "voxel" ? 0 : (r.level == "subvoxel" ? 1 : 2);
  } else {
    s.color = r.variant == "simple" ? 3 : (r.variant == "optimized" ? 4 : 5);
    s.dashed = r.level == "exact";
  }
  return s;
}

// Voxel sizes beside the oracle's and the explicit pairs' points (the other sphere modes have
// the same errors: their labels would overlap); FCL's points carry their variant.
std::string PointLabel(const AccuracyRow& r) {
  if (r.method == "fcl") return r.query == "distance" ? "" : r.variant;
  if (r.query == "oracle" || r.variant == "explicit") return VoxelLabel(r.voxel_mm);
  return "";
}

// The Pareto front of the p95 chart, by time.
ChartSeries ParetoSeries(const std::vector<AccuracyRow>& rows) {
  std::vector<const AccuracyRow*> front;
  for (const AccuracyRow& r : rows) {
    if (r.pareto) front.push_back(&r);
  }
  std::sort(front.begin(), front.end(),
            [](const AccuracyRow* a, const AccuracyRow* b) { return a->us.median < b->us.median; });
  ChartSeries s;
  s.name = "Pareto front (missing <= 1%)";
  s.color = 7;
  s.dashed = true;
  for (const AccuracyRow* r : front) {
    s.x.push_back(r->us.median);
    s.y.push_back(std::max(r->p95_err_mm, kErrorFloorMm));
  }
  return s;
}

// Median time against the p95 (or max) error, one series per method; no series: no chart.
LineChart ErrorChart(const std::vector<AccuracyRow>& rows, bool p95, const std::string& subtitle) {
  LineChart c;
  c.title = std::string("Speed against accuracy: ") + (p95 ? "95th percentile" : "maximum") +
            " contact-distance error against query time";
  c.subtitle = subtitle;
  c.x_label = "median query time, us (thread CPU, log)";
  c.y_label = std::string(p95 ? "p95" : "max") + " error of claimed distances, mm (log)";
  c.log_x = c.log_y = true;
  std::map<std::string, std::size_t> index;
  for (const AccuracyRow& r : rows) {
    const double err = p95 ? r.p95_err_mm : r.max_err_mm;
    if (!std::isfinite(err) || !(r.us.median > 0)) continue;
    const std::string key = SeriesName(r);
    if (!index.count(key)) {
      index[key] = c.series.size();
      c.series.push_back(NewSeries(r));
    }
    ChartSeries& s = c.series[index[key]];
    s.x.push_back(r.us.median);
    s.y.push_back(std::max(err, kErrorFloorMm));
    s.labels.push_back(PointLabel(r));
  }
  if (c.series.empty()) return c;
  if (p95) {
    ChartSeries front = ParetoSeries(rows);
    if (!front.x.empty()) c.series.push_back(front);
  }
  // The second, unlabelled line only extends the axis a decade below the
  // floor, so points on the floor stay off the frame.
  c.references = {{kErrorFloorMm, "error < 1e-5 mm"}, {0.1 * kErrorFloorMm, ""}};
  c.width = 1300;
  c.height = 800;
  return c;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> AccuracyCharts(
    const std::vector<AccuracyRow>& rows, const std::string& subtitle) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const bool p95 : {true, false}) {
    const LineChart c = ErrorChart(rows, p95, subtitle);
    if (c.series.empty()) continue;
    files.emplace_back(p95 ? "accuracy.png" : "accuracy-max.png", RenderLineChartPng(c));
  }
  return files;
}

}  // namespace occlude::app
