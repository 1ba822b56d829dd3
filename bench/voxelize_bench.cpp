// Micro-benchmarks of the sparse voxelization: Voxelize on the real jaws of case
// a-bite-3shape at 0.2 and 0.1 mm (skipped when the shared data folder is absent;
// $OCCLUDE_DATA_DIR overrides its place), a sphere as a synthetic fallback, and
// the exact triangle/box test. Counters report the stage times, the voxel counts
// and the grid's memory.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>

#include "data_dir.h"
#include "occlude/collision/triangle_box.h"
#include "occlude/collision/voxel_grid.h"
#include "occlude/io/mesh_io.h"

namespace {

using occlude::collision::Voxelize;
using occlude::collision::VoxelizeOptions;
using occlude::collision::VoxelizeStats;

/// The real loader; an empty mesh when the file cannot be read.
occlude::io::TriangleMesh ReadBinaryStl(const std::filesystem::path& file) {
  try {
    return occlude::io::LoadMesh(file);
  } catch (const occlude::io::MeshError&) {
    return {};
  }
}

/// The mesh of a-bite-3shape's `jaw` ("upper" or "lower"), loaded once; empty when absent.
const occlude::io::TriangleMesh& Jaw(const std::string& jaw) {
  static std::map<std::string, occlude::io::TriangleMesh> cache;
  auto it = cache.find(jaw);
  if (it == cache.end()) {
    const auto file = occlude::bench::SharedCaseDir("a-bite-3shape") / (jaw + ".stl");
    occlude::io::TriangleMesh mesh;
    if (std::filesystem::exists(file)) mesh = ReadBinaryStl(file);
    it = cache.emplace(jaw, std::move(mesh)).first;
  }
  return it->second;
}

void Report(benchmark::State& state, const occlude::collision::VoxelGrid& grid,
            const VoxelizeStats& st) {
  state.counters["surface_s"] = st.seconds_surface;
  state.counters["proximity_s"] = st.seconds_proximity;
  state.counters["interior_s"] = st.seconds_interior;
  state.counters["surface"] = static_cast<double>(st.surface_voxels);
  state.counters["proximity"] = static_cast<double>(st.proximity_voxels);
  state.counters["interior"] = static_cast<double>(st.interior_voxels);
  state.counters["pairs"] = static_cast<double>(grid.triangle_indices.size());
  state.counters["tests"] = static_cast<double>(st.triangle_voxel_tests);
  state.counters["closed"] = static_cast<double>(st.closed_components);
  state.counters["odd_rows"] = static_cast<double>(st.interior_odd_rows);
  state.counters["MB"] = static_cast<double>(grid.MemoryBytes()) / 1e6;
}

void Run(benchmark::State& state, const occlude::io::TriangleMesh& mesh, double voxel_mm) {
  VoxelizeOptions options;
  options.voxel_size_mm = voxel_mm;
  VoxelizeStats st;
  occlude::collision::VoxelGrid grid;
  for (auto _ : state) {
    grid = Voxelize(mesh, options, &st);
    benchmark::DoNotOptimize(grid.surface_keys.data());
  }
  Report(state, grid, st);
}

void BM_VoxelizeJaw(benchmark::State& state, const std::string& jaw, double voxel_mm) {
  const auto& mesh = Jaw(jaw);
  if (mesh.empty()) {
    state.SkipWithError("a-bite-3shape not found (set OCCLUDE_DATA_DIR)");
    return;
  }
  Run(state, mesh, voxel_mm);
}
BENCHMARK_CAPTURE(BM_VoxelizeJaw, upper_0_2mm, std::string("upper"), 0.2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelizeJaw, lower_0_2mm, std::string("lower"), 0.2)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelizeJaw, upper_0_1mm, std::string("upper"), 0.1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_VoxelizeJaw, lower_0_1mm, std::string("lower"), 0.1)
    ->Unit(benchmark::kMillisecond);

/// A closed UV sphere of radius 10 mm with about 2 * rings * segments triangles.
occlude::io::TriangleMesh Sphere(int rings, int segments) {
  occlude::io::TriangleMesh m;
  const double pi = std::acos(-1.0), r = 10.0;
  m.vertices.emplace_back(0, 0, r);
  for (int i = 1; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const double th = pi * i / rings, ph = 2 * pi * j / segments;
      m.vertices.emplace_back(r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph),
                              r * std::cos(th));
    }
  }
  m.vertices.emplace_back(0, 0, -r);
  const int south = static_cast<int>(m.vertices.size()) - 1;
  auto at = [&](int i, int j) { return 1 + (i - 1) * segments + j % segments; };
  for (int j = 0; j < segments; ++j) m.triangles.emplace_back(0, at(1, j), at(1, j + 1));
  for (int i = 1; i < rings - 1; ++i) {
    for (int j = 0; j < segments; ++j) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  for (int j = 0; j < segments; ++j)
    m.triangles.emplace_back(south, at(rings - 1, j + 1), at(rings - 1, j));
  m.parts.push_back({"sphere", 0});
  m.triangle_part.assign(m.triangles.size(), 0);
  m.ComputeFaceNormals();
  return m;
}

void BM_VoxelizeSphere(benchmark::State& state) {
  static const occlude::io::TriangleMesh mesh = Sphere(200, 400);
  Run(state, mesh, 0.2);
}
BENCHMARK(BM_VoxelizeSphere)->Unit(benchmark::kMillisecond);

void BM_TriangleBoxOverlap(benchmark::State& state) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> p(3 * 1024);
  for (auto& v : p) v = Eigen::Vector3d(u(rng), u(rng), u(rng));
  const Eigen::Vector3d center(0.1, -0.2, 0.05), half(0.3, 0.3, 0.3);
  std::size_t n = 0, hits = 0;
  for (auto _ : state) {
    const std::size_t k = 3 * (n++ % 1024);
    hits += occlude::collision::TriangleBoxOverlap(center, half, p[k], p[k + 1], p[k + 2]);
  }
  benchmark::DoNotOptimize(hits);
}
BENCHMARK(BM_TriangleBoxOverlap);

}  // namespace
