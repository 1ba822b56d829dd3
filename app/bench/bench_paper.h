// `occlude bench --paper`: the result figures of the reference paper (Le Jeune
// et al., "Analysis of collision detection using Implicit Sphere Tree ...")
// reproduced on one jaw mesh, and its query-rate figure on a jaw pair:
//   Fig. 4  surface voxel count against the voxel size,
//   Fig. 5  voxelization time,
//   Figs. 7-8  octree build time, node and leaf counts,
//   Fig. 9  total sphere volume per level, simple and optimized spheres,
//   Fig. 10 query rate against distance, simple / optimized / explicit spheres
//           (the existing `occlude bench` sweep, RunBench, at far offsets too).
// Build times are thread CPU time of the calling thread (median of a few
// builds); the growth with the voxel size is fitted as a power law.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench.h"

namespace occlude::app {

struct PaperOptions {
  std::vector<double> voxels_mm = {10.0, 5.0, 1.0, 0.8, 0.4, 0.2, 0.1};
  std::vector<double> sweep_voxels_mm = {0.8, 0.2};  ///< Fig. 10
  /// Fig. 10 offsets along the occlusal axis, mm (the paper descends from ~40 steps).
  std::vector<double> offsets_mm = {40.0, 30.0, 25.0, 20.0, 15.0, 10.0, 7.0,  5.0, 3.0,
                                    2.0,  1.0,  0.5,  0.2,  0.1,  0.0,  -0.1, -0.2};
  int reps = 9;        ///< jittered poses per offset (Fig. 10)
  int build_reps = 3;  ///< timed builds per voxel size (one when a build takes over 2 s)
  std::uint32_t seed = 1;
  double delta_mm = 0.0;  ///< Fig. 10 pairs band: 0 = the paper's overlap test
  bool fcl = true;
  bool sweep = true;  ///< run Fig. 10 when a pair is given
  std::ostream* log = nullptr;
};

/// Figs. 4, 5, 7, 8 at one voxel size.
struct PaperBuildRow {
  double voxel_mm = 0.0;
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();  ///< our sparse grid's extent, voxels
  long paper_grid_n = 0;         ///< the paper's grid edge: next power of 2 >= ceil(l / s)
  double paper_dense_cells = 0;  ///< n^3: the voxels the paper's build visits
  std::size_t surface = 0, proximity = 0, interior = 0, triangle_tests = 0;
  double voxelize_us = 0, octree_us = 0;  ///< thread CPU, median of build_reps
  int build_reps = 0;
  double surface_s = 0, proximity_s = 0, interior_s = 0;  ///< voxelization stages (wall)
  double explicit_s = 0;                                  ///< explicit spheres and slabs (wall)
  /// The whole SphereTree::Build (voxels, octree, explicit spheres and slabs,
  /// distance bound), thread CPU, one build.
  double tree_us = 0;
  std::size_t nodes = 0, leaves = 0;
  int levels = 0;
  std::size_t paper_min_nodes = 0;  ///< the paper's estimate: leaves + ceil(./8) per level
  std::size_t bytes_grid = 0, bytes_octree = 0, bytes_explicit = 0;
};

/// Fig. 9 at one voxel size and level.
struct PaperLevelRow {
  double voxel_mm = 0.0;
  int level = 0;  ///< 0 = leaves (voxels)
  std::size_t nodes = 0;
  double simple_mm3 = 0, optimized_mm3 = 0;
  /// One simple sphere of a node of this level, sqrt(3)/2 * pi * (s 2^level)^3:
  /// the paper's unit sqrt(3)/2 * pi * 2^(3(L-1)) * s^3 with its L = level + 1.
  double unit_mm3 = 0;
};

/// y = a * x^exponent fitted by least squares on log-log axes.
struct PowerFit {
  std::string what;     ///< e.g. "surface voxels vs voxel size"
  double exponent = 0;  ///< slope of log y against log x
  double r2 = 0;        ///< coefficient of determination of the log-log fit
  double x_lo = 0, x_hi = 0;
  std::size_t points = 0;
};
PowerFit FitPowerLaw(const std::vector<double>& x, const std::vector<double>& y,
                     const std::string& what);

/// y = intercept + slope * x by least squares (a fixed cost plus a cost per item).
struct AffineFit {
  std::string what;
  double intercept = 0, slope = 0, r2 = 0;
  double x_lo = 0, x_hi = 0;
  std::size_t points = 0;
};
AffineFit FitAffine(const std::vector<double>& x, const std::vector<double>& y,
                    const std::string& what);

struct PaperResult {
  std::string mesh_name;
  std::size_t triangles = 0;
  Eigen::Vector3d extent_mm = Eigen::Vector3d::Zero();
  double area_mm2 = 0;
  std::vector<PaperBuildRow> builds;
  std::vector<PaperLevelRow> levels;
  std::vector<BenchRow> sweep;  ///< Fig. 10; empty without a jaw pair
  std::vector<PowerFit> fits;
  std::vector<AffineFit> affine;
  std::string pair_name;  ///< the jaw pair of Fig. 10 (empty without one)
};

/// Figs. 4-9 on `mesh`; Fig. 10 on `pair` when not null.
PaperResult RunPaper(std::shared_ptr<const io::TriangleMesh> mesh, const std::string& mesh_name,
                     const BenchCase* pair, const PaperOptions& options);

/// Every output file (name, bytes): CSVs, charts, the summary.
std::vector<std::pair<std::string, std::string>> PaperFiles(const PaperResult& result,
                                                            const std::string& machine);

/// The paper's own figures (its jaw: 73.0 x 27.5 x 60.9 mm, 106,696 triangles).
struct PaperReference {
  static constexpr double kVoxel[] = {10.0, 5.0, 1.0};
  static constexpr double kSurfaceVoxels[] = {92.0, 397.0, 11120.0};
  static constexpr double kNodesAt1mm = 14600.0;
  static constexpr double kMinNodesAt1mm = 12700.0;
  static constexpr double kLongestEdgeMm = 73.0;
};

}  // namespace occlude::app
