// The measurements of `occlude bench --paper` (see bench_paper.h).
#include "bench/bench_paper.h"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "occlude/angles.h"
#include "occlude/collision/octree.h"
#include "occlude/collision/sphere_tree.h"
#include "occlude/collision/voxel_grid.h"

namespace occlude::app {
namespace {

void Log(const PaperOptions& options, const std::string& line) {
  if (options.log) *options.log << "paper: " << line << std::endl;
}

// Median thread-CPU microseconds of `build` over up to `reps` runs (one run
// when the first takes over 2 s); *runs = how many.
template <class F>
double MedianBuildMicros(int reps, int* runs, F&& build) {
  std::vector<double> us;
  for (int i = 0; i < std::max(1, reps); ++i) {
    const double t0 = ThreadCpuSeconds();
    build();
    us.push_back(1e6 * (ThreadCpuSeconds() - t0));
    if (us.front() > 2e6) break;
  }
  *runs = static_cast<int>(us.size());
  return Summarize(&us).median;
}

long NextPowerOfTwo(long v) {
  long n = 1;
  while (n < v) n *= 2;
  return n;
}

std::size_t PaperMinNodes(std::size_t leaves) {
  std::size_t total = leaves, level = leaves;
  while (level > 1) {
    level = (level + 7) / 8;
    total += level;
  }
  return total;
}

}  // namespace

PowerFit FitPowerLaw(const std::vector<double>& x, const std::vector<double>& y,
                     const std::string& what) {
  PowerFit fit;
  fit.what = what;
  std::vector<double> lx, ly;
  for (std::size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (!(x[i] > 0) || !(y[i] > 0) || !std::isfinite(x[i]) || !std::isfinite(y[i])) continue;
    lx.push_back(std::log(x[i]));
    ly.push_back(std::log(y[i]));
    fit.x_lo = fit.points == 0 ? x[i] : std::min(fit.x_lo, x[i]);
    fit.x_hi = fit.points == 0 ? x[i] : std::max(fit.x_hi, x[i]);
    ++fit.points;
  }
  if (fit.points < 2) return fit;
  const double n = static_cast<double>(fit.points);
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < lx.size(); ++i) mx += lx[i] / n, my += ly[i] / n;
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < lx.size(); ++i) {
    sxx += (lx[i] - mx) * (lx[i] - mx);
    sxy += (lx[i] - mx) * (ly[i] - my);
    syy += (ly[i] - my) * (ly[i] - my);
  }
  if (sxx <= 0) return fit;
  fit.exponent = sxy / sxx;
  fit.r2 = syy > 0 ? (sxy * sxy) / (sxx * syy) : 1.0;
  return fit;
}

AffineFit FitAffine(const std::vector<double>& x, const std::vector<double>& y,
                    const std::string& what) {
  AffineFit fit;
  fit.what = what;
  const std::size_t n = std::min(x.size(), y.size());
  fit.points = n;
  if (n < 2) return fit;
  fit.x_lo = *std::min_element(x.begin(), x.begin() + static_cast<long>(n));
  fit.x_hi = *std::max_element(x.begin(), x.begin() + static_cast<long>(n));
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i)
    mx += x[i] / static_cast<double>(n), my += y[i] / static_cast<double>(n);
  double sxx = 0, sxy = 0, syy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
    syy += (y[i] - my) * (y[i] - my);
  }
  if (sxx <= 0) return fit;
  fit.slope = sxy / sxx;
  fit.intercept = my - fit.slope * mx;
  fit.r2 = syy > 0 ? (sxy * sxy) / (sxx * syy) : 1.0;
  return fit;
}

namespace {

// The paper's own figures fitted alike: its surface voxel counts (10, 5, 1 mm) and the dense
// grid it visits (n^3) at our fine voxel sizes `s`.
void AddPaperFits(const std::vector<double>& s, PaperResult* result) {
  std::vector<double> ps(std::begin(PaperReference::kVoxel), std::end(PaperReference::kVoxel));
  std::vector<double> pc(std::begin(PaperReference::kSurfaceVoxels),
                         std::end(PaperReference::kSurfaceVoxels));
  result->fits.push_back(FitPowerLaw(ps, pc, "paper: surface voxels vs voxel size (10, 5, 1 mm)"));
  std::vector<double> dense;
  for (const double v : s) {
    dense.push_back(std::pow(static_cast<double>(NextPowerOfTwo(
                                 static_cast<long>(std::ceil(PaperReference::kLongestEdgeMm / v)))),
                             3.0));
  }
  result->fits.push_back(FitPowerLaw(s, dense, "paper: dense grid cells n^3 vs voxel size"));
}

// Figs. 4, 5, 7 and 8 at voxel size s: voxelization and octree timed (median of
// build_reps), then the whole tree once more for the explicit spheres; Fig. 9's rows (the
// sphere volumes per level) go to `levels`.
PaperBuildRow MeasureBuild(const std::shared_ptr<const io::TriangleMesh>& mesh, double s,
                           double longest, const PaperOptions& options,
                           std::vector<PaperLevelRow>* levels) {
  PaperBuildRow row;
  row.voxel_mm = s;
  row.paper_grid_n = NextPowerOfTwo(static_cast<long>(std::ceil(longest / s)));
  row.paper_dense_cells = std::pow(static_cast<double>(row.paper_grid_n), 3.0);
  collision::SphereTreeOptions tree_options;
  tree_options.voxelize.voxel_size_mm = s;
  {
    collision::VoxelGrid grid;
    collision::VoxelizeStats stats;
    row.voxelize_us = MedianBuildMicros(options.build_reps, &row.build_reps, [&] {
      grid = collision::Voxelize(*mesh, tree_options.voxelize, &stats);
    });
    int octree_runs = 0;
    collision::Octree octree;
    row.octree_us = MedianBuildMicros(options.build_reps, &octree_runs,
                                      [&] { octree = collision::BuildOctree(grid); });
    row.dims = grid.dims;
    row.surface = stats.surface_voxels;
    row.proximity = stats.proximity_voxels;
    row.interior = stats.interior_voxels;
    row.triangle_tests = stats.triangle_voxel_tests;
    row.surface_s = stats.seconds_surface;
    row.proximity_s = stats.seconds_proximity;
    row.interior_s = stats.seconds_interior;
  }
  const double t0 = ThreadCpuSeconds();
  const collision::SphereTree tree = collision::SphereTree::Build(mesh, tree_options);
  row.tree_us = 1e6 * (ThreadCpuSeconds() - t0);
  const collision::SphereTreeStats& st = tree.stats();
  row.explicit_s = st.seconds_explicit;
  row.nodes = st.nodes;
  row.leaves = st.leaves;
  row.levels = tree.octree().top_level + 1;
  row.paper_min_nodes = PaperMinNodes(st.leaves);
  row.bytes_grid = st.bytes_grid;
  row.bytes_octree = st.bytes_octree;
  row.bytes_explicit = st.bytes_explicit;
  for (const collision::LevelStats& ls : st.levels) {
    PaperLevelRow level;
    level.voxel_mm = s;
    level.level = ls.level;
    level.nodes = ls.nodes;
    level.simple_mm3 = ls.simple_volume_mm3;
    level.optimized_mm3 = ls.optimized_volume_mm3;
    level.unit_mm3 = std::sqrt(3.0) / 2.0 * kPi * std::pow(std::ldexp(s, ls.level), 3.0);
    levels->push_back(level);
  }
  return row;
}

// The growth fits: power laws on the fine end (s <= 1 mm, where per-voxel work dominates the
// per-triangle work; the paper's cubic claim is about this range) and between the two finest
// sizes, affine fits over every size, and the paper's own figures.
void FitGrowth(PaperResult* result) {
  std::vector<double> s, surface, voxelize, octree, nodes, bytes;
  for (const PaperBuildRow& r : result->builds) {
    if (r.voxel_mm > 1.0 + 1e-9) continue;
    s.push_back(r.voxel_mm);
    surface.push_back(static_cast<double>(r.surface));
    voxelize.push_back(r.voxelize_us);
    octree.push_back(r.octree_us);
    nodes.push_back(static_cast<double>(r.nodes));
    bytes.push_back(static_cast<double>(r.bytes_grid + r.bytes_octree));
  }
  std::vector<double> s2, voxelize2, octree2;
  for (std::size_t i = s.size() >= 2 ? s.size() - 2 : 0; i < s.size(); ++i) {
    s2.push_back(s[i]);
    voxelize2.push_back(voxelize[i]);
    octree2.push_back(octree[i]);
  }
  std::vector<double> all_surface, all_voxelize, all_octree;
  for (const PaperBuildRow& r : result->builds) {
    all_surface.push_back(static_cast<double>(r.surface));
    all_voxelize.push_back(r.voxelize_us);
    all_octree.push_back(r.octree_us);
  }
  result->affine = {FitAffine(all_surface, all_voxelize, "voxelization CPU us vs surface voxels"),
                    FitAffine(all_surface, all_octree, "octree build CPU us vs surface voxels")};
  result->fits = {FitPowerLaw(s, surface, "surface voxels vs voxel size"),
                  FitPowerLaw(s, voxelize, "voxelization CPU time vs voxel size"),
                  FitPowerLaw(s, octree, "octree build CPU time vs voxel size"),
                  FitPowerLaw(s, nodes, "octree nodes vs voxel size"),
                  FitPowerLaw(s, bytes, "grid + octree bytes vs voxel size"),
                  FitPowerLaw(surface, voxelize, "voxelization CPU time vs surface voxels"),
                  FitPowerLaw(surface, octree, "octree build CPU time vs surface voxels"),
                  FitPowerLaw(s2, voxelize2, "voxelization CPU time vs voxel size, two finest"),
                  FitPowerLaw(s2, octree2, "octree build CPU time vs voxel size, two finest")};
  AddPaperFits(s, result);
}

}  // namespace

PaperResult RunPaper(std::shared_ptr<const io::TriangleMesh> mesh, const std::string& mesh_name,
                     const BenchCase* pair, const PaperOptions& options) {
  PaperResult result;
  result.mesh_name = mesh_name;
  result.triangles = mesh->num_triangles();
  result.extent_mm = mesh->Bounds().sizes();
  result.area_mm2 = mesh->SurfaceArea();
  const double longest = result.extent_mm.maxCoeff();
  for (const double s : options.voxels_mm) {
    Log(options, mesh_name + " at " + std::to_string(s) + " mm");
    result.builds.push_back(MeasureBuild(mesh, s, longest, options, &result.levels));
  }
  FitGrowth(&result);
  if (pair != nullptr && options.sweep) {
    BenchOptions bench;
    bench.voxels_mm = options.sweep_voxels_mm;
    bench.offsets_mm = options.offsets_mm;
    bench.reps = options.reps;
    bench.seed = options.seed;
    bench.delta_mm = options.delta_mm;
    bench.fcl = options.fcl;
    bench.openvdb = false;  // the paper's Fig. 10 compares with FCL only
    bench.log = options.log;
    Log(options, "Fig. 10: the query-rate sweep on " + pair->name);
    result.pair_name = pair->name;
    result.sweep = RunBench(*pair, bench);
  }
  return result;
}

}  // namespace occlude::app
