// Voxelize: coverage and exactness of the surface voxels, analytic counts for
// boxes, the interior of a sphere against |c - centre| < r, open meshes,
// proximity on the outward side, scaling with the voxel size, the memory
// estimate, errors, determinism, and the real meshes when ../shared/data exists.
#include "occlude/collision/voxel_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <regex>

#include "occlude/collision/floor_int.h"
#include "occlude/collision/morton.h"
#include "occlude/collision/triangle_box.h"
#include "occlude/io/mesh_io.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

using V = Eigen::Vector3d;

/// The real loader; an empty mesh when the file cannot be read.
io::TriangleMesh ReadBinaryStl(const std::filesystem::path& file) {
  try {
    return io::LoadMesh(file);
  } catch (const io::MeshError&) {
    return {};
  }
}

/// Index of surface voxel ijk in grid.surface_keys, or -1.
long SurfaceIndex(const VoxelGrid& g, const Eigen::Vector3i& ijk) {
  if ((ijk.array() < 0).any() || (ijk.array() >= g.dims.array()).any()) return -1;
  const auto key = MortonEncode(ijk);
  const auto it = std::lower_bound(g.surface_keys.begin(), g.surface_keys.end(), key);
  return it != g.surface_keys.end() && *it == key ? it - g.surface_keys.begin() : -1;
}

bool ListsTriangle(const VoxelGrid& g, long v, std::uint32_t t) {
  const auto b = g.triangle_indices.begin();
  return std::find(b + g.triangles_begin(static_cast<std::size_t>(v)),
                   b + g.triangles_end(static_cast<std::size_t>(v)),
                   t) != b + g.triangles_end(static_cast<std::size_t>(v));
}

bool ExactOverlap(const io::TriangleMesh& m, const VoxelGrid& g, std::size_t t,
                  const Eigen::Vector3i& ijk) {
  return TriangleBoxOverlap(g.VoxelCenter(ijk), V::Constant(g.SurfaceHalfSize()), m.corner(t, 0),
                            m.corner(t, 1), m.corner(t, 2));
}

/// Loose triangles of random size (0.05 .. 3 mm) and orientation in a 10 mm cube.
io::TriangleMesh RandomSoup(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-5, 5), size(0.05, 3.0);
  std::normal_distribution<double> g(0, 1);
  io::TriangleMesh m;
  for (int t = 0; t < n; ++t) {
    const V a(pos(rng), pos(rng), pos(rng));
    const double sz = size(rng);
    m.vertices.push_back(a);
    m.vertices.push_back(a + sz * V(g(rng), g(rng), g(rng)));
    m.vertices.push_back(a + sz * V(g(rng), g(rng), g(rng)));
    m.triangles.emplace_back(3 * t, 3 * t + 1, 3 * t + 2);
  }
  m.parts.push_back({"soup", 0});
  m.triangle_part.assign(m.triangles.size(), 0);
  m.ComputeFaceNormals();
  return m;
}

VoxelizeOptions Options(double s) {
  VoxelizeOptions o;
  o.voxel_size_mm = s;
  return o;
}

/// Random points of every triangle lie in Surface voxels that list the triangle.
void ExpectCovered(const io::TriangleMesh& m, const VoxelGrid& g, int samples, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> w(0, 1);
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    for (int s = 0; s < samples; ++s) {
      double x = w(rng), y = w(rng);
      if (x + y > 1) {
        x = 1 - x;
        y = 1 - y;
      }
      const V p = m.corner(t, 0) + x * (m.corner(t, 1) - m.corner(t, 0)) +
                  y * (m.corner(t, 2) - m.corner(t, 0));
      const Eigen::Vector3i ijk = g.VoxelOf(p);
      ASSERT_EQ(g.Classify(ijk), VoxelClass::kSurface)
          << "triangle " << t << " p " << p.transpose() << " voxel " << ijk.transpose() << " exact "
          << ExactOverlap(m, g, t, ijk) << " s " << g.voxel_size_mm << " centre "
          << g.VoxelCenter(ijk).transpose();
      ASSERT_TRUE(ListsTriangle(g, SurfaceIndex(g, ijk), static_cast<std::uint32_t>(t)))
          << "triangle " << t;
    }
  }
}

/// Every listed triangle passes the exact test on its voxel, and every voxel
/// near a triangle that passes the exact test lists it (the lists are exact).
void ExpectExactLists(const io::TriangleMesh& m, const VoxelGrid& g) {
  std::size_t listed = 0;
  for (std::size_t v = 0; v < g.num_surface(); ++v) {
    const Eigen::Vector3i ijk = MortonDecode(g.surface_keys[v]);
    ASSERT_LT(g.triangles_begin(v), g.triangles_end(v));
    for (auto n = g.triangles_begin(v); n < g.triangles_end(v); ++n) {
      ASSERT_TRUE(ExactOverlap(m, g, g.triangle_indices[n], ijk)) << "voxel " << v;
      if (n > g.triangles_begin(v)) {
        ASSERT_LT(g.triangle_indices[n - 1], g.triangle_indices[n]);
      }
    }
  }
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    Eigen::AlignedBox3d box;
    for (int k = 0; k < 3; ++k) box.extend(m.corner(t, k));
    const Eigen::Vector3i lo = g.VoxelOf(box.min()) - Eigen::Vector3i::Ones();
    const Eigen::Vector3i hi = g.VoxelOf(box.max()) + Eigen::Vector3i::Ones();
    for (int k = lo.z(); k <= hi.z(); ++k) {
      for (int j = lo.y(); j <= hi.y(); ++j) {
        for (int i = lo.x(); i <= hi.x(); ++i) {
          if (!ExactOverlap(m, g, t, {i, j, k})) continue;
          ++listed;
          const long v = SurfaceIndex(g, {i, j, k});
          ASSERT_GE(v, 0) << "triangle " << t << " voxel " << i << " " << j << " " << k;
          ASSERT_TRUE(ListsTriangle(g, v, static_cast<std::uint32_t>(t)));
        }
      }
    }
  }
  EXPECT_EQ(listed, g.triangle_indices.size());
}

/// Sorted keys, CSR sizes, disjoint classes, runs sorted and inside the grid.
void ExpectWellFormed(const VoxelGrid& g) {
  auto increasing = [](const std::vector<std::uint64_t>& k) {
    return std::adjacent_find(k.begin(), k.end(), std::greater_equal<>()) == k.end();
  };
  EXPECT_TRUE(increasing(g.surface_keys));
  EXPECT_TRUE(increasing(g.proximity_keys));
  ASSERT_EQ(g.triangle_offsets.size(), g.surface_keys.size() + 1);
  EXPECT_EQ(g.triangle_offsets.back(), g.triangle_indices.size());
  for (const auto key : g.proximity_keys) {
    EXPECT_FALSE(std::binary_search(g.surface_keys.begin(), g.surface_keys.end(), key));
    EXPECT_EQ(g.Classify(MortonDecode(key)), VoxelClass::kProximity);
  }
  for (std::size_t n = 0; n < g.interior_runs.size(); ++n) {
    const VoxelRun& r = g.interior_runs[n];
    ASSERT_LT(r.x_begin, r.x_end);
    ASSERT_GE(r.x_begin, 0);
    ASSERT_LE(r.x_end, g.dims.x());
    if (n > 0) {
      const VoxelRun& p = g.interior_runs[n - 1];
      ASSERT_TRUE(std::make_tuple(p.z, p.y, p.x_end) <= std::make_tuple(r.z, r.y, r.x_begin));
    }
    for (int x = r.x_begin; x < r.x_end; ++x) {
      ASSERT_EQ(g.Classify({x, r.y, r.z}), VoxelClass::kInterior);
    }
  }
}

TEST(VoxelizeTest, BoxSphereAndSoupAreCoveredExactly) {
  const io::TriangleMesh meshes[] = {test::MakeBox(V(0.13, -0.4, 0.27), V(2.3, 1.1, 1.9)),
                                     test::MakeSphere(V(0.3, -0.2, 0.1), 2.0, 12, 24),
                                     RandomSoup(40, 5)};
  for (const auto& mesh : meshes) {
    for (const double s : {0.25, 0.4}) {
      const VoxelGrid g = Voxelize(mesh, Options(s));
      ExpectCovered(mesh, g, 40, 11);
      ExpectExactLists(mesh, g);
      ExpectWellFormed(g);
    }
  }
}

// Box [0, 2] x [0, 3] x [0, 4] at s = 0.5: faces on voxel boundaries touch two
// layers; shifted by a quarter, faces through voxel centres touch one layer.
TEST(VoxelizeTest, AxisAlignedBoxCountsMatchAnalytic) {
  const V size(2, 3, 4);
  const double s = 0.5;
  const Eigen::Vector3i n(4, 6, 8);
  VoxelizeStats st;
  const VoxelGrid on = Voxelize(test::MakeBox(V::Zero(), size), Options(s), &st);
  EXPECT_EQ(on.num_surface(),
            static_cast<std::size_t>((n.array() + 2).prod() - (n.array() - 2).prod()));
  EXPECT_EQ(st.interior_voxels, static_cast<std::size_t>((n.array() - 2).prod()));
  EXPECT_EQ(st.closed_components, 1u);
  const VoxelGrid mid =
      Voxelize(test::MakeBox(V::Constant(0.25), V::Constant(0.25) + size), Options(s), &st);
  EXPECT_EQ(mid.num_surface(),
            static_cast<std::size_t>((n.array() + 1).prod() - (n.array() - 1).prod()));
  EXPECT_EQ(st.interior_voxels, static_cast<std::size_t>((n.array() - 1).prod()));
  EXPECT_EQ(st.interior_odd_rows, 0u);
  ExpectWellFormed(on);
  ExpectWellFormed(mid);
}

TEST(VoxelizeTest, SphereInteriorMatchesAnalytic) {
  const V center(0.11, -0.23, 0.37);
  const double r = 3.0, s = 0.25;
  const io::TriangleMesh mesh = test::MakeSphere(center, r, 48, 96);
  VoxelizeStats st;
  const VoxelGrid g = Voxelize(mesh, Options(s), &st);
  EXPECT_EQ(st.closed_components, 1u);
  EXPECT_EQ(st.interior_odd_rows, 0u);
  std::size_t inside = 0, disagree_near = 0;
  for (int k = 0; k < g.dims.z(); ++k) {
    for (int j = 0; j < g.dims.y(); ++j) {
      for (int i = 0; i < g.dims.x(); ++i) {
        const VoxelClass c = g.Classify({i, j, k});
        ASSERT_EQ(g.IsInterior({i, j, k}), c == VoxelClass::kInterior) << i << " " << j << " " << k;
        const double d = (g.VoxelCenter({i, j, k}) - center).norm();
        const bool expected = d < r && c != VoxelClass::kSurface;
        inside += expected;
        if ((c == VoxelClass::kInterior) != expected) {
          ASSERT_LT(std::abs(d - r), s) << i << " " << j << " " << k;
          ++disagree_near;
        }
      }
    }
  }
  EXPECT_GT(inside, 5000u);
  EXPECT_LT(disagree_near, inside / 100);
  for (const Eigen::Vector3i& outside :
       {Eigen::Vector3i(-1, 0, 0), Eigen::Vector3i(0, g.dims.y(), 0),
        Eigen::Vector3i(0, 0, g.dims.z() + 5)}) {
    EXPECT_FALSE(g.IsInterior(outside));
  }
  std::size_t run_voxels = 0;
  for (const VoxelRun& run : g.interior_runs)
    run_voxels += static_cast<std::size_t>(run.x_end - run.x_begin);
  EXPECT_EQ(st.interior_voxels, run_voxels);
  ExpectWellFormed(g);
}

TEST(VoxelizeTest, OpenBoxHasNoInteriorButSurfaceAndProximity) {
  io::TriangleMesh box = test::MakeBox(V(0, 0, 0), V(2, 2, 2));
  box.triangles.resize(10);  // drop the last face
  box.face_normals.resize(10);
  box.triangle_part.resize(10);
  VoxelizeStats st;
  const VoxelGrid g = Voxelize(box, Options(0.25), &st);
  EXPECT_GT(g.num_surface(), 0u);
  EXPECT_GT(g.proximity_keys.size(), 0u);
  EXPECT_TRUE(g.interior_runs.empty());
  EXPECT_EQ(st.closed_components, 0u);
  EXPECT_EQ(st.open_components, 1u);
}

// Proximity voxels of a sphere lie outside the inscribed polyhedron, within
// `layers` voxels (Chebyshev) of a surface voxel; the first shell has no gaps.
TEST(VoxelizeTest, SphereProximityIsOutwardAndGapFree) {
  const V center(0.05, 0.1, -0.15);
  const double r = 3.0, s = 0.2;
  const io::TriangleMesh mesh = test::MakeSphere(center, r, 48, 96);
  double inner = r;  // smallest distance from the centre to a face plane
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    inner = std::min(inner, mesh.face_normals[t].dot(mesh.corner(t, 0) - center));
  }
  for (const int layers : {1, 2}) {
    VoxelizeOptions o = Options(s);
    o.proximity_layers = layers;
    const VoxelGrid g = Voxelize(mesh, o);
    ASSERT_GT(g.proximity_keys.size(), 0u);
    for (const auto key : g.proximity_keys) {
      const Eigen::Vector3i q = MortonDecode(key);
      const double d = (g.VoxelCenter(q) - center).norm();
      ASSERT_GT(d, inner);
      ASSERT_LT(d, r + (layers + 1) * s * std::sqrt(3.0));
      bool near_surface = false;
      for (int dz = -layers; dz <= layers && !near_surface; ++dz)
        for (int dy = -layers; dy <= layers && !near_surface; ++dy)
          for (int dx = -layers; dx <= layers && !near_surface; ++dx)
            near_surface = SurfaceIndex(g, q + Eigen::Vector3i(dx, dy, dz)) >= 0;
      ASSERT_TRUE(near_surface);
    }
    // Every voxel whose centre is 1 to layers - 0.2 voxels outside the sphere and
    // that is not a surface voxel is a proximity voxel.
    std::size_t shell = 0, missed = 0;
    for (int k = 0; k < g.dims.z(); ++k)
      for (int j = 0; j < g.dims.y(); ++j)
        for (int i = 0; i < g.dims.x(); ++i) {
          const double d = (g.VoxelCenter({i, j, k}) - center).norm() - r;
          if (d < s || d > (layers - 0.2) * s) continue;
          const VoxelClass c = g.Classify({i, j, k});
          if (c == VoxelClass::kSurface) continue;
          ++shell;
          missed += c != VoxelClass::kProximity;
        }
    EXPECT_EQ(missed, 0u) << "layers " << layers << " shell " << shell;
  }
}

/// Options for a surface-only voxelization.
VoxelizeOptions SurfaceOnly(double s) {
  VoxelizeOptions o = Options(s);
  o.classify_proximity = false;
  o.classify_interior = false;
  return o;
}

TEST(VoxelizeTest, SurfaceCountScalesWithArea) {
  const io::TriangleMesh sphere = test::MakeSphere(V(0.1, 0.2, 0.3), 10.0, 48, 96);
  const double ratio = static_cast<double>(Voxelize(sphere, SurfaceOnly(0.2)).num_surface()) /
                       static_cast<double>(Voxelize(sphere, SurfaceOnly(0.4)).num_surface());
  EXPECT_GT(ratio, 3.3);
  EXPECT_LT(ratio, 4.7);
}

TEST(VoxelizeTest, MandibleSurfaceCountScalesWithArea) {
  const auto dir = test::SharedDataDir();
  if (!dir || !std::filesystem::exists(*dir / "single" / "mandible-ct.stl")) {
    GTEST_SKIP() << "shared data folder with single/mandible-ct.stl not found";
  }
  const io::TriangleMesh mesh = ReadBinaryStl(*dir / "single" / "mandible-ct.stl");
  ASSERT_EQ(mesh.num_triangles(), 36226u);
  VoxelizeStats st;
  const VoxelGrid fine = Voxelize(mesh, SurfaceOnly(0.4));
  const VoxelGrid coarse = Voxelize(mesh, Options(0.8), &st);
  const double ratio =
      static_cast<double>(fine.num_surface()) / static_cast<double>(coarse.num_surface());
  EXPECT_GT(ratio, 3.3);
  EXPECT_LT(ratio, 4.7);
  EXPECT_GE(st.closed_components, 1u);
  EXPECT_GT(st.interior_voxels, 0u);
  ExpectWellFormed(coarse);
  const double est = static_cast<double>(EstimateVoxelizeBytes(mesh, Options(0.8)));
  EXPECT_GT(est, 0.5 * static_cast<double>(coarse.MemoryBytes()));
  EXPECT_LT(est, 2.0 * static_cast<double>(coarse.MemoryBytes()));
}

TEST(VoxelizeTest, EstimateWithinFactorTwoOfMemory) {
  const io::TriangleMesh meshes[] = {
      test::MakeSphere(V(0.1, 0.2, 0.3), 6.0, 48, 96), test::MakeSphere(V(0, 0, 0), 5.0, 8, 16),
      test::MakeBox(V(0.1, 0.2, 0.3), V(12.1, 7.2, 9.3)), RandomSoup(300, 8)};
  for (const auto& mesh : meshes) {
    for (const double s : {0.2, 0.4}) {
      const VoxelGrid g = Voxelize(mesh, Options(s));
      const double est = static_cast<double>(EstimateVoxelizeBytes(mesh, Options(s)));
      const double actual = static_cast<double>(g.MemoryBytes());
      EXPECT_GT(est, 0.5 * actual) << "s " << s << " triangles " << mesh.num_triangles();
      EXPECT_LT(est, 2.0 * actual) << "s " << s << " triangles " << mesh.num_triangles();
    }
  }
}

TEST(VoxelizeTest, BadVoxelSizesThrow) {
  const io::TriangleMesh box = test::MakeBox(V(0, 0, 0), V(1, 1, 1));
  for (const double s : {0.0, -0.1, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(Voxelize(box, Options(s)), VoxelizeError) << s;
  }
  VoxelizeOptions o = Options(0.2);
  o.proximity_layers = -1;
  EXPECT_THROW(Voxelize(box, o), VoxelizeError);
}

/// The number after "smallest voxel size that fits is about " in msg, or NaN.
double SuggestedSize(const std::string& msg) {
  std::smatch m;
  if (!std::regex_search(msg, m,
                         std::regex("smallest voxel size that fits is about ([0-9.eE+-]+) mm"))) {
    return std::nan("");
  }
  return std::stod(m[1]);
}

TEST(VoxelizeTest, GridOverflowThrowsWithFittingSize) {
  io::TriangleMesh wide;
  wide.vertices = {V(0, 0, 0), V(1e6, 0, 0), V(1e6, 1, 0), V(0, 1, 0)};
  wide.triangles = {Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(0, 2, 3)};
  wide.parts.push_back({"strip", 0});
  wide.triangle_part.assign(2, 0);
  wide.ComputeFaceNormals();
  try {
    Voxelize(wide, Options(0.001));
    FAIL() << "no VoxelizeError";
  } catch (const VoxelizeError& e) {
    const double fit = SuggestedSize(e.what());
    EXPECT_GE(fit, 1e6 / kMortonMaxCoord) << e.what();
    EXPECT_LT(fit, 1.01e6 / kMortonMaxCoord) << e.what();
    EXPECT_NE(std::string(e.what()).find("0.001"), std::string::npos) << e.what();
  }
}

TEST(VoxelizeTest, MemoryBudgetThrowsWithFittingSize) {
  const io::TriangleMesh sphere = test::MakeSphere(V(0, 0, 0), 10.0, 32, 64);
  VoxelizeOptions o = Options(0.05);
  o.memory_budget_bytes = 2'000'000;
  try {
    Voxelize(sphere, o);
    FAIL() << "no VoxelizeError";
  } catch (const VoxelizeError& e) {
    const double fit = SuggestedSize(e.what());
    ASSERT_GT(fit, 0.05) << e.what();
    o.voxel_size_mm = fit;
    EXPECT_LE(EstimateVoxelizeBytes(sphere, o), o.memory_budget_bytes);
    o.voxel_size_mm = 0.98 * fit;
    EXPECT_GT(EstimateVoxelizeBytes(sphere, o), o.memory_budget_bytes);
    o.voxel_size_mm = fit;
    EXPECT_NO_THROW(Voxelize(sphere, o));
  }
}

TEST(VoxelizeTest, Deterministic) {
  io::TriangleMesh mesh = test::MakeSphere(V(0.1, 0.2, 0.3), 4.0, 24, 48);
  mesh.Append(RandomSoup(100, 9));
  const VoxelGrid a = Voxelize(mesh, Options(0.2));
  const VoxelGrid b = Voxelize(mesh, Options(0.2));
  EXPECT_EQ(a.surface_keys, b.surface_keys);
  EXPECT_EQ(a.triangle_offsets, b.triangle_offsets);
  EXPECT_EQ(a.triangle_indices, b.triangle_indices);
  EXPECT_EQ(a.proximity_keys, b.proximity_keys);
  ASSERT_EQ(a.interior_runs.size(), b.interior_runs.size());
  for (std::size_t n = 0; n < a.interior_runs.size(); ++n) {
    EXPECT_EQ(a.interior_runs[n].x_begin, b.interior_runs[n].x_begin);
    EXPECT_EQ(a.interior_runs[n].x_end, b.interior_runs[n].x_end);
  }
  EXPECT_EQ(a.origin_F, b.origin_F);
  EXPECT_EQ(a.dims, b.dims);
}

TEST(VoxelizeTest, OptionsAndEmptyMesh) {
  const io::TriangleMesh sphere = test::MakeSphere(V(0, 0, 0), 2.0, 16, 32);
  VoxelizeOptions o = Options(0.2);
  o.classify_proximity = false;
  o.classify_interior = false;
  const VoxelGrid g = Voxelize(sphere, o);
  EXPECT_GT(g.num_surface(), 0u);
  EXPECT_TRUE(g.proximity_keys.empty());
  EXPECT_TRUE(g.interior_runs.empty());
  EXPECT_EQ(g.Classify({-1, 0, 0}), VoxelClass::kUndefined);
  EXPECT_EQ(g.Classify(g.dims), VoxelClass::kUndefined);
  const VoxelGrid empty = Voxelize(io::TriangleMesh{}, Options(0.2));
  EXPECT_EQ(empty.num_surface(), 0u);
  EXPECT_EQ(empty.Classify({0, 0, 0}), VoxelClass::kUndefined);
}

// Two closed shells sharing a rim with an open sheet (like the teeth and gingiva
// of a 3Shape export): the tooth made of crown + cap is closed, the sheet open.
TEST(VoxelizeTest, ShellSharingRimWithOpenSheetIsClosed) {
  io::TriangleMesh box = test::MakeBox(V(0, 0, 0), V(2, 2, 2));
  // An open sheet in the plane z = 0 around the box's bottom face, sharing its
  // four bottom edges: a square ring from [-1, 3]^2 to the box's bottom square.
  const int base = static_cast<int>(box.vertices.size());
  for (const V& p : {V(-1, -1, 0), V(3, -1, 0), V(-1, 3, 0), V(3, 3, 0)}) box.vertices.push_back(p);
  // Bottom corners of MakeBox: 0 (0,0,0), 1 (2,0,0), 2 (0,2,0), 3 (2,2,0).
  const int ring[4][4] = {{0, 1, base + 1, base},
                          {1, 3, base + 3, base + 1},
                          {3, 2, base + 2, base + 3},
                          {2, 0, base, base + 2}};
  for (const auto& q : ring) {
    box.triangles.emplace_back(q[0], q[2], q[1]);
    box.triangles.emplace_back(q[0], q[3], q[2]);
  }
  box.triangle_part.assign(box.triangles.size(), 0);
  box.ComputeFaceNormals();
  VoxelizeStats st;
  const VoxelGrid g = Voxelize(box, Options(0.25), &st);
  EXPECT_EQ(st.closed_components, 1u);
  EXPECT_EQ(st.open_components, 1u);
  EXPECT_EQ(st.interior_voxels, 6u * 6u * 6u);
  ExpectWellFormed(g);
}

TEST(VoxelizeTest, RealJawsHaveClosedTeeth) {
  OCCLUDE_REQUIRE_CASE(dir, "a-bite-3shape");
  for (const char* jaw : {"upper.stl", "lower.stl"}) {
    const io::TriangleMesh mesh = ReadBinaryStl(dir / jaw);
    ASSERT_GT(mesh.num_triangles(), 100000u);
    VoxelizeStats st;
    const VoxelGrid g = Voxelize(mesh, Options(0.8), &st);
    EXPECT_EQ(st.closed_components, 14u) << jaw;  // 14 teeth, each a closed shell
    EXPECT_EQ(st.interior_odd_rows, 0u) << jaw;
    ExpectWellFormed(g);
    ExpectCovered(mesh, g, 1, 3);
    const double est = static_cast<double>(EstimateVoxelizeBytes(mesh, Options(0.8)));
    EXPECT_GT(est, 0.5 * static_cast<double>(g.MemoryBytes()));
    EXPECT_LT(est, 2.0 * static_cast<double>(g.MemoryBytes()));
  }
}

// FloorInt and FloorInt64 are std::floor on the values the grids give them: integers, their
// neighbours an ulp away on either side, halves, zero of both signs and the ends of the range.
TEST(FloorInt, MatchesStdFloor) {
  std::vector<double> xs = {0.0,     -0.0,         0.5,           -0.5,         1e-300,
                            -1e-300, 2147483646.5, -2147483647.0, -2147483646.5};
  for (int i = -2100; i <= 2100; ++i) {
    const double x = i;
    for (const double v : {x, std::nextafter(x, -1e9), std::nextafter(x, 1e9), x + 0.5})
      xs.push_back(v);
  }
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-3e6, 3e6);
  for (int i = 0; i < 10000; ++i) xs.push_back(u(rng));
  for (const double x : xs)
    EXPECT_EQ(static_cast<double>(detail::FloorInt(x)), std::floor(x)) << std::hexfloat << x;
  // FloorInt64 (the samples' cell keys) on the same values and past the 32-bit range.
  for (const double x : {4294967296.5, -4294967296.5, 9.0e18, -9.0e18, -9.2e18 + 0.5})
    xs.push_back(x);
  for (const double x : xs)
    EXPECT_EQ(static_cast<double>(detail::FloorInt64(x)), std::floor(x)) << std::hexfloat << x;
}

// VoxelOf (FloorInt on its quotients) gives the voxel of the floor-and-nudge rule with libm's
// floor: for points on faces, an ulp off them, and at random.
TEST(VoxelGrid, VoxelOfIsTheFloorAndNudgeRule) {
  VoxelGrid g;
  g.voxel_size_mm = 0.2;
  g.origin_F = V(-13.37, 4.1, -0.3);
  g.dims = Eigen::Vector3i(200, 150, 90);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> cell(-5, 205);
  std::uniform_real_distribution<double> w(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    V p;
    for (int a = 0; a < 3; ++a) {
      const double face = g.origin_F[a] + g.voxel_size_mm * cell(rng);
      const int kind = i % 4;
      p[a] = kind == 0   ? face
             : kind == 1 ? std::nextafter(face, -1e9)
             : kind == 2 ? std::nextafter(face, 1e9)
                         : face + g.voxel_size_mm * w(rng);
    }
    const Eigen::Vector3i v = g.VoxelOf(p);
    for (int a = 0; a < 3; ++a) {
      double q = std::floor((p[a] - g.origin_F[a]) / g.voxel_size_mm);
      const double half = 0.5 * g.voxel_size_mm;
      if (p[a] - (g.origin_F[a] + g.voxel_size_mm * (q + 0.5)) > half) q += 1.0;
      if (p[a] - (g.origin_F[a] + g.voxel_size_mm * (q + 0.5)) < -half) q -= 1.0;
      EXPECT_EQ(v[a], static_cast<int>(q)) << p.transpose();
    }
  }
}

}  // namespace
}  // namespace occlude::collision
