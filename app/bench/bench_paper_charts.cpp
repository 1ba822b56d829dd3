// The charts of `occlude bench --paper` (see bench_paper_charts_internal.h): one per
// figure, against the voxel size on log-log axes with s^-2 and s^-3 guides,
// the paper's numbers where it gives them, and Fig. 10 against the offset.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "base/text_format.h"
#include "bench/bench_paper_charts_internal.h"
#include "chart/chart.h"

namespace occlude::app {
namespace {

// A chart against the voxel size, log-log, one point label per voxel size.
LineChart VoxelChart(const std::string& title, const std::string& subtitle,
                     const std::string& y_label) {
  LineChart c;
  c.title = title;
  c.subtitle = subtitle;
  c.x_label = "voxel size s, mm (log)";
  c.y_label = y_label;
  c.log_x = c.log_y = true;
  return c;
}

template <class F>
ChartSeries BuildSeries(const PaperResult& r, const std::string& name, int color, F&& value) {
  ChartSeries s;
  s.name = name;
  s.color = color;
  for (const PaperBuildRow& b : r.builds) {
    s.x.push_back(b.voxel_mm);
    s.y.push_back(value(b));
  }
  return s;
}

// A dashed guide y = y0 * (s / s0)^exponent through the finest measured point.
ChartSeries Guide(const PaperResult& r, double s0, double y0, double exponent,
                  const std::string& name, int color) {
  ChartSeries s;
  s.name = name;
  s.color = color;
  s.dashed = true;
  for (const PaperBuildRow& b : r.builds) {
    if (b.voxel_mm > 1.0 + 1e-9) continue;  // over the fitted range only
    s.x.push_back(b.voxel_mm);
    s.y.push_back(y0 * std::pow(b.voxel_mm / s0, exponent));
  }
  return s;
}

// Guides of slope -2 (surface) and -3 (volume) through the finest point of `value`.
template <class F>
void AddGuides(const PaperResult& r, LineChart* c, F&& value) {
  const auto finest = std::min_element(
      r.builds.begin(), r.builds.end(),
      [](const PaperBuildRow& a, const PaperBuildRow& b) { return a.voxel_mm < b.voxel_mm; });
  if (finest == r.builds.end() || !(value(*finest) > 0)) return;
  c->series.push_back(Guide(r, finest->voxel_mm, value(*finest), -2.0, "~ s^-2 (surface)", 7));
  c->series.push_back(Guide(r, finest->voxel_mm, value(*finest), -3.0, "~ s^-3 (volume)", 8));
}

std::string FitText(const PaperResult& r, const std::string& prefix) {
  for (const PowerFit& f : r.fits) {
    if (f.what.rfind(prefix, 0) == 0 && f.points >= 2) {
      return "fitted exponent " + FixedOrEmpty(f.exponent, 2) + " for s in [" +
             ShortNumber(f.x_lo) + ", " + ShortNumber(f.x_hi) + "] mm";
    }
  }
  return "";
}

void BuildCharts(const PaperResult& r, const std::string& sub,
                 std::vector<std::pair<std::string, std::string>>* files) {
  {
    LineChart c = VoxelChart("Fig. 4: surface voxels against voxel size (" + r.mesh_name + ")",
                             sub + " | " + FitText(r, "surface voxels"), "voxels (log)");
    ChartSeries ours = BuildSeries(r, "ours: surface voxels", 0,
                                   [](const auto& b) { return static_cast<double>(b.surface); });
    c.series.push_back(ours);
    ChartSeries paper;
    paper.name = "paper (73 x 27.5 x 61 mm jaw)";
    paper.color = 3;
    paper.markers_only = true;
    for (int i = 0; i < 3; ++i) {
      paper.x.push_back(PaperReference::kVoxel[i]);
      paper.y.push_back(PaperReference::kSurfaceVoxels[i]);
      paper.labels.push_back(ShortNumber(PaperReference::kSurfaceVoxels[i]));
    }
    c.series.push_back(paper);
    ChartSeries dense = BuildSeries(r, "paper's dense grid on this mesh, n^3", 1,
                                    [](const auto& b) { return b.paper_dense_cells; });
    dense.dashed = true;
    c.series.push_back(dense);
    AddGuides(r, &c, [](const PaperBuildRow& b) { return static_cast<double>(b.surface); });
    files->emplace_back("fig4-surface-voxels.png", RenderLineChartPng(c));
  }
  {
    LineChart c = VoxelChart("Fig. 5: voxelization time against voxel size (" + r.mesh_name + ")",
                             sub + " | " + FitText(r, "voxelization CPU time vs voxel"),
                             "thread CPU time, ms (log)");
    c.series.push_back(BuildSeries(r, "voxelization (all classes)", 0,
                                   [](const auto& b) { return b.voxelize_us / 1e3; }));
    AddGuides(r, &c, [](const PaperBuildRow& b) { return b.voxelize_us / 1e3; });
    files->emplace_back("fig5-voxelize-time.png", RenderLineChartPng(c));
  }
  {
    LineChart c = VoxelChart("Fig. 7: octree build time against voxel size (" + r.mesh_name + ")",
                             sub + " | " + FitText(r, "octree build CPU time vs voxel"),
                             "thread CPU time, ms (log)");
    c.series.push_back(
        BuildSeries(r, "octree (thread CPU)", 0, [](const auto& b) { return b.octree_us / 1e3; }));
    c.series.push_back(BuildSeries(r, "whole tree, with explicit", 2,
                                   [](const auto& b) { return b.tree_us / 1e3; }));
    AddGuides(r, &c, [](const PaperBuildRow& b) { return b.octree_us / 1e3; });
    files->emplace_back("fig7-octree-time.png", RenderLineChartPng(c));
  }
  {
    LineChart c =
        VoxelChart("Fig. 8: octree nodes and leaves against voxel size (" + r.mesh_name + ")",
                   sub + " | " + FitText(r, "octree nodes"), "count (log)");
    c.series.push_back(
        BuildSeries(r, "nodes", 0, [](const auto& b) { return static_cast<double>(b.nodes); }));
    c.series.push_back(BuildSeries(r, "leaves (= surface voxels)", 1,
                                   [](const auto& b) { return static_cast<double>(b.leaves); }));
    ChartSeries bound = BuildSeries(r, "paper's minimum estimate", 2, [](const auto& b) {
      return static_cast<double>(b.paper_min_nodes);
    });
    bound.dashed = true;
    c.series.push_back(bound);
    ChartSeries paper;
    paper.name = "paper, 1 mm: 14,600 / 11,120";
    paper.color = 3;
    paper.markers_only = true;
    paper.x = {1.0, 1.0};
    paper.y = {PaperReference::kNodesAt1mm, PaperReference::kSurfaceVoxels[2]};
    c.series.push_back(paper);
    files->emplace_back("fig8-octree-nodes.png", RenderLineChartPng(c));
  }
}

void VolumeChart(const PaperResult& r, const std::string& sub,
                 std::vector<std::pair<std::string, std::string>>* files) {
  LineChart c;
  c.title = "Fig. 9: total sphere volume per level (" + r.mesh_name + ")";
  c.subtitle = sub + " | unit: one simple sphere of a node of the level";
  c.x_label = "octree level (0 = voxels)";
  c.y_label = "total volume, in units (log)";
  c.log_y = true;
  // The paper's 1 mm and our 0.2 mm when measured, else the two finest sizes.
  std::vector<double> sizes;
  for (const PaperBuildRow& b : r.builds) sizes.push_back(b.voxel_mm);
  std::sort(sizes.begin(), sizes.end());
  std::vector<double> shown;
  for (const double v : {1.0, 0.2}) {
    if (std::any_of(sizes.begin(), sizes.end(), [&](double s) { return std::abs(s - v) < 1e-9; }))
      shown.push_back(v);
  }
  if (shown.empty()) shown.assign(sizes.begin(), sizes.begin() + std::min<long>(2, sizes.size()));
  int color = 0;
  for (const double v : shown) {
    ChartSeries simple, optimized;
    simple.name = "simple, " + ShortNumber(v) + " mm voxels";
    optimized.name = "optimized, " + ShortNumber(v) + " mm voxels";
    simple.color = optimized.color = color++;
    optimized.dashed = true;
    for (const PaperLevelRow& l : r.levels) {
      if (std::abs(l.voxel_mm - v) > 1e-9) continue;
      simple.x.push_back(l.level);
      simple.y.push_back(l.simple_mm3 / l.unit_mm3);
      optimized.x.push_back(l.level);
      optimized.y.push_back(l.optimized_mm3 / l.unit_mm3);
    }
    if (simple.x.empty()) continue;
    c.series.push_back(simple);
    c.series.push_back(optimized);
  }
  if (!c.series.empty()) files->emplace_back("fig9-sphere-volume.png", RenderLineChartPng(c));
}

void SweepCharts(const PaperResult& r, const std::string& sub,
                 std::vector<std::pair<std::string, std::string>>* files) {
  std::vector<double> offsets;
  std::set<double> voxels;
  for (const BenchRow& b : r.sweep) {
    if (b.query == "build") continue;
    if (std::find(offsets.begin(), offsets.end(), b.offset_mm) == offsets.end())
      offsets.push_back(b.offset_mm);
    if (std::isfinite(b.voxel_mm)) voxels.insert(b.voxel_mm);
  }
  if (offsets.empty()) return;
  std::vector<std::string> labels;
  for (const double o : offsets) labels.push_back(ShortNumber(o));
  for (const char* query : {"boolean", "pairs"}) {
    LineChart c;
    c.title = std::string("Fig. 10: ") +
              (query == std::string("boolean") ? "boolean collision query"
                                               : "all colliding voxel pairs") +
              " against distance";
    c.subtitle = sub;
    c.x_label = "offset along the occlusal axis, mm (0 = registered bite; the paper's distance)";
    c.y_label = "queries per second, Hz (log)";
    c.log_y = true;
    c.x_categories = labels;
    c.references = {{1000.0, "1 kHz (haptic)"}};
    // One colour per sphere mode (the paper's comparison); finer voxels dashed.
    bool finer = false;
    for (auto v = voxels.rbegin(); v != voxels.rend(); ++v, finer = true) {
      int color = 0;
      for (const char* variant : {"simple", "optimized", "explicit"}) {
        ChartSeries s;
        s.name = std::string("IST ") + variant + ", " + ShortNumber(*v) + " mm";
        s.color = color++;
        s.dashed = finer;
        for (const BenchRow& b : r.sweep) {
          if (b.method != "ist" || b.variant != variant || b.query != query || b.voxel_mm != *v ||
              !(b.us.median > 0))
            continue;
          const auto it = std::find(offsets.begin(), offsets.end(), b.offset_mm);
          s.x.push_back(static_cast<double>(it - offsets.begin()));
          s.y.push_back(1e6 / b.us.median);
        }
        c.series.push_back(s);
      }
    }
    const std::string fcl_query = query == std::string("boolean") ? "boolean" : "collide-all";
    ChartSeries f;
    f.name = "FCL OBB " + fcl_query;
    f.color = 7;
    f.dashed = true;
    for (const BenchRow& b : r.sweep) {
      if (b.method != "fcl" || b.variant != "obb" || b.query != fcl_query || !(b.us.median > 0))
        continue;
      const auto it = std::find(offsets.begin(), offsets.end(), b.offset_mm);
      f.x.push_back(static_cast<double>(it - offsets.begin()));
      f.y.push_back(1e6 / b.us.median);
    }
    if (!f.x.empty()) c.series.push_back(f);
    files->emplace_back(std::string("fig10-") + query + ".png", RenderLineChartPng(c));
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> PaperCharts(const PaperResult& r,
                                                             const std::string& machine) {
  std::vector<std::pair<std::string, std::string>> files;
  const std::string sub = r.mesh_name + " | " + machine;
  if (!r.builds.empty()) {
    BuildCharts(r, sub, &files);
    VolumeChart(r, sub, &files);
  }
  SweepCharts(r, r.pair_name + " | " + machine + " | thread CPU, median of jittered poses", &files);
  return files;
}

}  // namespace occlude::app
