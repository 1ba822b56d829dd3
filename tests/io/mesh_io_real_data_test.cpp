// Real 3Shape exports from the shared data folder (skipped when it is absent):
// triangle counts, mm-scale bounds, load time, and a jaw from per-tooth files.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <set>

#include "occlude/io/mesh_io.h"
#include "test_common.h"

namespace occlude::io {
namespace {

namespace fs = std::filesystem;

// Loads `file`, printing and returning the wall time in seconds.
TriangleMesh TimedLoad(const fs::path& file, LoadReport* report, double* seconds) {
  const auto start = std::chrono::steady_clock::now();
  TriangleMesh mesh = LoadMesh(file, {}, report);
  *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "[ timing   ] " << file.string() << ": " << mesh.num_triangles() << " triangles, "
            << mesh.num_vertices() << " vertices in " << *seconds * 1000 << " ms\n";
  return mesh;
}

void ExpectJawScale(const TriangleMesh& mesh) {
  const Eigen::Vector3d size = mesh.Bounds().sizes();
  EXPECT_GT(size.maxCoeff(), 30.0) << size.transpose();
  EXPECT_LT(size.maxCoeff(), 120.0) << size.transpose();
  EXPECT_GT(size.minCoeff(), 5.0) << size.transpose();
}

TEST(MeshIoRealDataTest, ABiteUpperJaw) {
  OCCLUDE_REQUIRE_CASE(dir, "a-bite-3shape");
  LoadReport report;
  double seconds = 0;
  const TriangleMesh mesh = TimedLoad(dir / "upper.stl", &report, &seconds);
  EXPECT_EQ(mesh.num_triangles(), 137014u);
  EXPECT_EQ(mesh.ConsistencyError(), "");
  EXPECT_EQ(report.vertices_before_weld, 3u * 137014u);
  EXPECT_LT(mesh.num_vertices(), mesh.num_triangles());
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
  ExpectJawScale(mesh);
  // Load time is a benchmark figure, not a test condition (the machines are shared): printed.
  std::printf("b-open lower.stl: %zu triangles loaded in %.3f s\n", mesh.num_triangles(), seconds);
}

TEST(MeshIoRealDataTest, BOpenLowerJawLoadsConsistent) {
  OCCLUDE_REQUIRE_CASE(dir, "b-open-3shape");
  LoadReport report;
  double seconds = 0;
  const TriangleMesh mesh = TimedLoad(dir / "lower.stl", &report, &seconds);
  EXPECT_EQ(mesh.num_triangles() + report.degenerate_triangles_dropped, 234629u);
  EXPECT_EQ(mesh.ConsistencyError(), "");
  ExpectJawScale(mesh);
  // Load time is a benchmark figure, not a test condition (the machines are shared): printed.
  std::printf("b-open lower.stl: %zu triangles loaded in %.3f s\n", mesh.num_triangles(), seconds);
}

TEST(MeshIoRealDataTest, ABiteTeethAsJawParts) {
  OCCLUDE_REQUIRE_CASE(dir, "a-bite-3shape");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir / "teeth")) {
    if (entry.path().extension() == ".stl") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty());
  LoadReport report;
  const TriangleMesh jaw = LoadJawParts(files, {}, &report);
  EXPECT_EQ(jaw.ConsistencyError(), "");
  ASSERT_EQ(jaw.parts.size(), files.size());
  std::set<int> expected_teeth;
  std::set<int> teeth;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const std::string stem = files[i].stem().string();
    EXPECT_EQ(jaw.parts[i].name, stem);
    EXPECT_EQ(jaw.parts[i].tooth_number, ToothNumberFromFileName(stem));
    if (stem.find("Jaw") != std::string::npos) {
      EXPECT_EQ(jaw.parts[i].tooth_number, 0) << stem;
    }
    if (jaw.parts[i].tooth_number == 0) continue;
    EXPECT_TRUE(teeth.insert(jaw.parts[i].tooth_number).second) << stem;
    expected_teeth.insert(std::stoi(stem.substr(stem.find('_') + 1)));
  }
  EXPECT_EQ(teeth, expected_teeth);
  EXPECT_GE(*teeth.begin(), 1);
  EXPECT_LE(*teeth.rbegin(), 32);
  EXPECT_EQ(teeth.size() + 2, files.size()) << "all but Tooth_UpperJaw and Tooth_LowerJaw";
  for (const std::string& warning : report.warnings) ADD_FAILURE() << warning;
}

}  // namespace
}  // namespace occlude::io
