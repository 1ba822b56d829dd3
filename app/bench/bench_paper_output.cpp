// Output files of `occlude bench --paper` (see bench_paper.h): one CSV per
// figure group, the fitted growth, a summary, and the charts (bench_paper_charts_internal.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "base/text_format.h"
#include "bench/bench_paper.h"
#include "bench/bench_paper_charts_internal.h"

namespace occlude::app {
namespace {

std::string BuildCsv(const PaperResult& r) {
  std::ostringstream csv;
  csv << "mesh,voxel_mm,dims_x,dims_y,dims_z,paper_grid_n,paper_dense_cells,surface_voxels,"
         "proximity_voxels,interior_voxels,triangle_voxel_tests,voxelize_us,octree_us,build_reps,"
         "voxelize_surface_s,voxelize_proximity_s,voxelize_interior_s,explicit_s,tree_us,nodes,"
         "leaves,"
         "levels,paper_min_nodes,bytes_grid,bytes_octree,bytes_explicit\n";
  for (const PaperBuildRow& b : r.builds) {
    csv << r.mesh_name << ',' << FixedOrEmpty(b.voxel_mm, 3) << ',' << b.dims.x() << ','
        << b.dims.y() << ',' << b.dims.z() << ',' << b.paper_grid_n << ','
        << FixedOrEmpty(b.paper_dense_cells, 0) << ',' << b.surface << ',' << b.proximity << ','
        << b.interior << ',' << b.triangle_tests << ',' << FixedOrEmpty(b.voxelize_us, 1) << ','
        << FixedOrEmpty(b.octree_us, 1) << ',' << b.build_reps << ','
        << FixedOrEmpty(b.surface_s, 4) << ',' << FixedOrEmpty(b.proximity_s, 4) << ','
        << FixedOrEmpty(b.interior_s, 4) << ',' << FixedOrEmpty(b.explicit_s, 4) << ','
        << FixedOrEmpty(b.tree_us, 1) << ',' << b.nodes << ',' << b.leaves << ',' << b.levels << ','
        << b.paper_min_nodes << ',' << b.bytes_grid << ',' << b.bytes_octree << ','
        << b.bytes_explicit << '\n';
  }
  return csv.str();
}

std::string LevelsCsv(const PaperResult& r) {
  std::ostringstream csv;
  csv << "mesh,voxel_mm,level,nodes,simple_mm3,optimized_mm3,unit_mm3,simple_units,"
         "optimized_units,optimized_over_simple\n";
  for (const PaperLevelRow& l : r.levels) {
    csv << r.mesh_name << ',' << FixedOrEmpty(l.voxel_mm, 3) << ',' << l.level << ',' << l.nodes
        << ',' << FixedOrEmpty(l.simple_mm3, 4) << ',' << FixedOrEmpty(l.optimized_mm3, 4) << ','
        << FixedOrEmpty(l.unit_mm3, 6) << ',' << FixedOrEmpty(l.simple_mm3 / l.unit_mm3, 3) << ','
        << FixedOrEmpty(l.optimized_mm3 / l.unit_mm3, 3) << ','
        << FixedOrEmpty(l.simple_mm3 > 0 ? l.optimized_mm3 / l.simple_mm3 : std::nan(""), 4)
        << '\n';
  }
  return csv.str();
}

std::string FitsCsv(const PaperResult& r) {
  std::ostringstream csv;
  csv << "what,kind,x_lo,x_hi,points,exponent,intercept,slope,r2\n";
  for (const PowerFit& f : r.fits) {
    csv << '"' << f.what << "\",power," << ShortNumber(f.x_lo) << ',' << ShortNumber(f.x_hi) << ','
        << f.points << ',' << FixedOrEmpty(f.exponent, 3) << ",,," << FixedOrEmpty(f.r2, 4) << '\n';
  }
  for (const AffineFit& f : r.affine) {
    csv << '"' << f.what << "\",affine," << ShortNumber(f.x_lo) << ',' << ShortNumber(f.x_hi) << ','
        << f.points << ",," << FixedOrEmpty(f.intercept, 2) << ',' << FixedOrEmpty(f.slope, 6)
        << ',' << FixedOrEmpty(f.r2, 4) << '\n';
  }
  return csv.str();
}

std::string SummaryText(const PaperResult& r, const std::string& machine) {
  std::ostringstream s;
  s << "mesh " << r.mesh_name << ": " << r.triangles << " triangles, "
    << FixedOrEmpty(r.extent_mm.x(), 1) << " x " << FixedOrEmpty(r.extent_mm.y(), 1) << " x "
    << FixedOrEmpty(r.extent_mm.z(), 1) << " mm, area " << FixedOrEmpty(r.area_mm2, 0) << " mm^2\n"
    << "machine: " << machine << "; build times: thread CPU, median of up to 3 builds\n\n"
    << "voxel_mm  surface  nodes  leaves  levels  voxelize_ms  octree_ms  surface*s^2/area\n";
  for (const PaperBuildRow& b : r.builds) {
    char line[200];
    std::snprintf(line, sizeof line, "%8g  %7zu  %5zu  %6zu  %6d  %11.2f  %9.2f  %16.3f\n",
                  b.voxel_mm, b.surface, b.nodes, b.leaves, b.levels, b.voxelize_us / 1e3,
                  b.octree_us / 1e3,
                  static_cast<double>(b.surface) * b.voxel_mm * b.voxel_mm / r.area_mm2);
    s << line;
  }
  s << "\naffine fits over every voxel size (y = intercept + slope * x):\n";
  for (const AffineFit& f : r.affine) {
    char line[200];
    std::snprintf(line, sizeof line, "  %-52s %.1f us + %.4f us per voxel  r2 %.4f\n",
                  f.what.c_str(), f.intercept, f.slope, f.r2);
    s << line;
  }
  s << "\npower-law fits (y ~ x^exponent, log-log least squares):\n";
  for (const PowerFit& f : r.fits) {
    char line[200];
    std::snprintf(line, sizeof line, "  %-52s exponent %6.3f  r2 %.4f  (%zu points, %g..%g)\n",
                  f.what.c_str(), f.exponent, f.r2, f.points, f.x_lo, f.x_hi);
    s << line;
  }
  return s.str();
}

}  // namespace

std::vector<std::pair<std::string, std::string>> PaperFiles(const PaperResult& r,
                                                            const std::string& machine) {
  std::vector<std::pair<std::string, std::string>> files = {
      {"paper-build.csv", BuildCsv(r)},
      {"paper-levels.csv", LevelsCsv(r)},
      {"paper-fits.csv", FitsCsv(r)},
      {"paper-summary.txt", SummaryText(r, machine)}};
  if (!r.sweep.empty()) files.emplace_back("paper-fig10.csv", BenchCsv(r.sweep));
  for (auto& chart : PaperCharts(r, machine)) files.push_back(std::move(chart));
  return files;
}

}  // namespace occlude::app
