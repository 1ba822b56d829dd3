// Micro-benchmarks of the signed distance on the real lower jaw of case
// a-bite-3shape (skipped when the shared data folder is absent; $OCCLUDE_DATA_DIR
// overrides its place): NarrowBandSdf build time and memory at 0.2 and 0.1 mm,
// Interpolate and Exact ns/call for points within 0.1 mm of the surface (random
// order and surface-coherent order), and the interpolation error against Exact
// (median, p95, max as counters, mm).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "data_dir.h"
#include "occlude/collision/morton.h"
#include "occlude/collision/signed_distance.h"
#include "occlude/io/mesh_io.h"

namespace {

using occlude::collision::NarrowBandSdf;
using occlude::collision::VoxelGrid;
using V = Eigen::Vector3d;

/// The lower jaw, loaded once (null when absent).
std::shared_ptr<const occlude::io::TriangleMesh> LowerJaw() {
  static const std::shared_ptr<const occlude::io::TriangleMesh> mesh = [] {
    const auto file = occlude::bench::SharedCaseDir("a-bite-3shape") / "lower.stl";
    if (!std::filesystem::exists(file)) return std::shared_ptr<const occlude::io::TriangleMesh>();
    return std::make_shared<const occlude::io::TriangleMesh>(occlude::io::LoadMesh(file));
  }();
  return mesh;
}

VoxelGrid Grid(const occlude::io::TriangleMesh& mesh, double s) {
  occlude::collision::VoxelizeOptions options;
  options.voxel_size_mm = s;
  options.classify_proximity = false;
  options.classify_interior = false;
  return occlude::collision::Voxelize(mesh, options);
}

/// Grid and field of the lower jaw at voxel size s, built once.
const NarrowBandSdf& Field(double s) {
  static std::map<double, NarrowBandSdf> cache;
  auto it = cache.find(s);
  if (it == cache.end()) {
    const auto mesh = LowerJaw();
    it = cache.emplace(s, NarrowBandSdf::Build(mesh, Grid(*mesh, s))).first;
  }
  return it->second;
}

/// n points within `reach` of the jaw surface (area-weighted triangle, random
/// point on it, random direction), fixed seed; `coherent` sorts them along the
/// surface (Morton order of 0.2 mm cells) instead of random order.
std::vector<V> NearSurface(std::size_t n, double reach, bool coherent) {
  const auto& m = *LowerJaw();
  std::vector<double> cumulative;
  double sum = 0.0;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    sum += 0.5 * (m.corner(t, 1) - m.corner(t, 0)).cross(m.corner(t, 2) - m.corner(t, 0)).norm();
    cumulative.push_back(sum);
  }
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<V> points;
  for (std::size_t i = 0; i < n; ++i) {
    const auto t = static_cast<std::size_t>(
        std::lower_bound(cumulative.begin(), cumulative.end(), u(rng) * sum) - cumulative.begin());
    double a = u(rng), b = u(rng);
    if (a + b > 1.0) {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    const V on = (1 - a - b) * m.corner(t, 0) + a * m.corner(t, 1) + b * m.corner(t, 2);
    points.push_back(on + reach * u(rng) * V(g(rng), g(rng), g(rng)).normalized());
  }
  if (coherent) {
    const V lo = m.Bounds().min() - V::Constant(1.0);
    auto key = [&](const V& p) {
      const Eigen::Vector3i c = ((p - lo) / 0.2).cast<int>();
      return occlude::collision::MortonEncode(c);
    };
    std::sort(points.begin(), points.end(),
              [&](const V& x, const V& y) { return key(x) < key(y); });
  }
  return points;
}

bool NoData(benchmark::State& state) {
  if (LowerJaw()) return false;
  state.SkipWithError("a-bite-3shape not found (set OCCLUDE_DATA_DIR)");
  return true;
}

void BM_SdfBuild(benchmark::State& state, double s) {
  if (NoData(state)) return;
  const auto mesh = LowerJaw();
  const VoxelGrid grid = Grid(*mesh, s);
  NarrowBandSdf sdf;
  for (auto _ : state) {
    sdf = NarrowBandSdf::Build(mesh, grid);
    benchmark::DoNotOptimize(sdf.num_band_voxels());
  }
  state.counters["band_voxels"] = static_cast<double>(sdf.num_band_voxels());
  state.counters["MB"] = static_cast<double>(sdf.MemoryBytes()) / 1e6;
  state.counters["grid_MB"] = static_cast<double>(grid.MemoryBytes()) / 1e6;
  state.counters["build_s"] = sdf.build_seconds();
}
BENCHMARK_CAPTURE(BM_SdfBuild, lower_0_2mm, 0.2)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_SdfBuild, lower_0_1mm, 0.1)->Unit(benchmark::kMillisecond)->Iterations(2);

/// `hot` cycles over 1024 points (their blocks stay in cache: the cost of the
/// arithmetic and the hash); otherwise 65,536 points spread over the whole jaw
/// (a DRAM miss on the 8-float block per call, the other jobs' load permitting).
void BM_SdfInterpolate(benchmark::State& state, double s, bool coherent, bool hot = false) {
  if (NoData(state)) return;
  const NarrowBandSdf& sdf = Field(s);
  const std::vector<V> points = NearSurface(hot ? 1 << 10 : 1 << 16, 0.1, coherent);
  std::size_t i = 0;
  double sum = 0.0;
  for (auto _ : state) {
    double d = 0.0;
    V grad;
    sdf.Interpolate(points[i++ & (points.size() - 1)], &d, &grad);
    sum += d + grad.x();
  }
  benchmark::DoNotOptimize(sum);
}
BENCHMARK_CAPTURE(BM_SdfInterpolate, hot_0_2mm, 0.2, false, true);
BENCHMARK_CAPTURE(BM_SdfInterpolate, random_0_2mm, 0.2, false);
BENCHMARK_CAPTURE(BM_SdfInterpolate, coherent_0_2mm, 0.2, true);
BENCHMARK_CAPTURE(BM_SdfInterpolate, random_0_1mm, 0.1, false);
BENCHMARK_CAPTURE(BM_SdfInterpolate, coherent_0_1mm, 0.1, true);

void BM_SdfExact(benchmark::State& state, double s, bool coherent) {
  if (NoData(state)) return;
  const NarrowBandSdf& sdf = Field(s);
  const std::vector<V> points = NearSurface(1 << 14, 0.1, coherent);
  std::size_t i = 0;
  double sum = 0.0;
  for (auto _ : state) {
    occlude::collision::SignedDistanceSample out;
    sdf.Exact(points[i++ & (points.size() - 1)], 0.3, &out);
    sum += out.distance;
  }
  benchmark::DoNotOptimize(sum);
}
BENCHMARK_CAPTURE(BM_SdfExact, random_0_2mm, 0.2, false);
BENCHMARK_CAPTURE(BM_SdfExact, coherent_0_2mm, 0.2, true);
BENCHMARK_CAPTURE(BM_SdfExact, random_0_1mm, 0.1, false);

/// Not a timing: |Interpolate - Exact| over 20,000 points within 0.1 mm (counters, mm).
void BM_SdfInterpolationError(benchmark::State& state, double s) {
  if (NoData(state)) return;
  const NarrowBandSdf& sdf = Field(s);
  const std::vector<V> points = NearSurface(20000, 0.1, false);
  std::vector<double> err;
  for (auto _ : state) {
    err.clear();
    for (const V& p : points) {
      double d = 0.0;
      occlude::collision::SignedDistanceSample e;
      if (sdf.Interpolate(p, &d) && sdf.Exact(p, 0.2, &e)) err.push_back(std::abs(d - e.distance));
    }
  }
  std::sort(err.begin(), err.end());
  auto at = [&](double q) {
    return err[static_cast<std::size_t>(q * static_cast<double>(err.size() - 1))];
  };
  state.counters["median_mm"] = at(0.5);
  state.counters["p95_mm"] = at(0.95);
  state.counters["p99_mm"] = at(0.99);
  state.counters["max_mm"] = err.back();
}
BENCHMARK_CAPTURE(BM_SdfInterpolationError, lower_0_2mm, 0.2)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SdfInterpolationError, lower_0_1mm, 0.1)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace
