// Decimation for display: the budget is met, the shape stays within the stated
// bound of the original (both ways, measured against the original triangles on a
// smooth sphere), kept vertices are original vertices, parts (tooth numbers)
// carry over, and the result is deterministic. Its cache encoding gives it back bit for bit,
// refuses malformed bytes or another mesh, and its key follows the mesh and the budget.
#include "occlude/io/display_decimation.h"

#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <stdexcept>
#include <string>

#include "occlude/collision/closest_point.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::io {
namespace {

// Smallest distance from p to any triangle of `mesh` (brute force).
double DistanceTo(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    best = std::min(best, collision::ClosestPointOnTriangle(p, mesh.corner(t, 0), mesh.corner(t, 1),
                                                            mesh.corner(t, 2))
                              .squared_distance);
  }
  return std::sqrt(best);
}

// Largest distance from the vertices and triangle centroids of `from` to `to`.
double OneSidedDistance(const TriangleMesh& from, const TriangleMesh& to) {
  double worst = 0.0;
  for (const Eigen::Vector3d& v : from.vertices) worst = std::max(worst, DistanceTo(to, v));
  for (std::size_t t = 0; t < from.num_triangles(); ++t) {
    const Eigen::Vector3d c = (from.corner(t, 0) + from.corner(t, 1) + from.corner(t, 2)) / 3.0;
    worst = std::max(worst, DistanceTo(to, c));
  }
  return worst;
}

TEST(DisplayDecimationTest, MeetsTheBudgetAndStaysWithinTheBoundOnASmoothSphere) {
  const TriangleMesh sphere = test::MakeSphere({3, -2, 1}, 10.0, 40, 80);  // ~6,300 triangles
  for (const std::size_t budget : {2000u, 600u}) {
    const DecimationResult r = DecimateForDisplay(sphere, {budget});
    EXPECT_LE(r.mesh.num_triangles(), budget);
    EXPECT_GT(r.mesh.num_triangles(), budget / 2) << "the search should use most of the budget";
    EXPECT_TRUE(r.mesh.ConsistencyError().empty()) << r.mesh.ConsistencyError();
    EXPECT_NEAR(r.error_bound_mm, std::sqrt(3.0) * r.cell_mm, test::kExactMm);
    EXPECT_LE(OneSidedDistance(r.mesh, sphere), r.error_bound_mm) << budget;  // the guarantee
    EXPECT_LE(OneSidedDistance(sphere, r.mesh), r.error_bound_mm) << budget;  // smooth: converse
    // The area is kept within a few percent (no holes, no folds).
    EXPECT_NEAR(r.mesh.SurfaceArea() / sphere.SurfaceArea(), 1.0, 0.03) << budget;
  }
}

TEST(DisplayDecimationTest, KeptVerticesAreOriginalVerticesAndPartsCarryOver) {
  const SyntheticJawPair pair = MakeSyntheticJawPair({20000, 1});
  const TriangleMesh& jaw = pair.upper_U;
  const DecimationResult r = DecimateForDisplay(jaw, {5000});
  ASSERT_LE(r.mesh.num_triangles(), 5000u);
  ASSERT_EQ(r.source_vertex.size(), r.mesh.num_vertices());
  ASSERT_EQ(r.mesh.parts.size(), jaw.parts.size());
  // The parts each original vertex belongs to.
  std::vector<std::set<std::int32_t>> parts_of(jaw.num_vertices());
  for (std::size_t t = 0; t < jaw.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) parts_of[jaw.triangles[t][k]].insert(jaw.triangle_part[t]);
  }
  std::set<int> teeth_before, teeth_after;
  for (const MeshPart& p : jaw.parts) teeth_before.insert(p.tooth_number);
  for (std::size_t t = 0; t < r.mesh.num_triangles(); ++t) {
    const std::int32_t part = r.mesh.triangle_part[t];
    teeth_after.insert(r.mesh.parts[part].tooth_number);
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = r.mesh.triangles[t][k];
      const std::int32_t source = r.source_vertex[v];
      EXPECT_EQ(r.mesh.vertices[v], jaw.vertices[source]);
      EXPECT_EQ(parts_of[source].count(part), 1u) << "triangle " << t << " moved to another part";
    }
  }
  EXPECT_EQ(teeth_after, teeth_before) << "every tooth keeps triangles";
  // Per-vertex values carry over by the source index.
  std::vector<float> values(jaw.num_vertices());
  for (std::size_t v = 0; v < values.size(); ++v) values[v] = 0.5f * static_cast<float>(v);
  const std::vector<float> kept = ValuesAtKeptVertices(r, values);
  ASSERT_EQ(kept.size(), r.mesh.num_vertices());
  for (std::size_t v = 0; v < kept.size(); ++v) EXPECT_EQ(kept[v], values[r.source_vertex[v]]);
  EXPECT_THROW(ValuesAtKeptVertices(r, std::vector<float>(3)), std::invalid_argument);
}

TEST(DisplayDecimationTest, IsDeterministicAndInvariantUnderTranslationOfTheGridOrigin) {
  const TriangleMesh sphere = test::MakeSphere({0, 0, 0}, 8.0, 30, 60);
  const DecimationResult a = DecimateForDisplay(sphere, {1000});
  const DecimationResult b = DecimateForDisplay(sphere, {1000});
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_EQ(a.source_vertex, b.source_vertex);
  // The grid starts at the bounds, so a translation gives the same choice of vertices.
  Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
  shift.translation() = Eigen::Vector3d(16.0, -32.0, 4.0);  // exact in binary: no rounding
  const DecimationResult moved = DecimateForDisplay(sphere.Transformed(shift), {1000});
  EXPECT_EQ(moved.source_vertex, a.source_vertex);
  EXPECT_EQ(moved.mesh.triangles, a.mesh.triangles);
}

TEST(DisplayDecimationTest, AMeshWithinTheBudgetIsReturnedUnchanged) {
  const TriangleMesh box = test::MakeBox({0, 0, 0}, {1, 2, 3});
  const DecimationResult r = DecimateForDisplay(box, {12});
  EXPECT_EQ(r.mesh.vertices, box.vertices);
  EXPECT_EQ(r.mesh.triangles, box.triangles);
  EXPECT_EQ(r.source_vertex, std::vector<std::int32_t>({0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(r.error_bound_mm, 0.0);
}

TEST(DisplayDecimationTest, ABadRequestNamesTheField) {
  const TriangleMesh box = test::MakeBox({0, 0, 0}, {1, 2, 3});
  try {
    DecimateForDisplay(box, {0});
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_triangles"), std::string::npos) << e.what();
  }
}

template <typename T>
bool SameBytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(DisplayDecimationTest, TheEncodingGivesTheResultBackBitForBit) {
  const TriangleMesh mesh = MakeSyntheticJawPair({20000, 3}).upper_U;
  const DecimationResult made = DecimateForDisplay(mesh, {6000});
  ASSERT_LT(made.mesh.num_triangles(), mesh.num_triangles());
  const DecimationResult back = DecodeDecimation(EncodeDecimation(made), mesh);
  EXPECT_TRUE(SameBytes(back.mesh.vertices, made.mesh.vertices));
  EXPECT_TRUE(SameBytes(back.mesh.triangles, made.mesh.triangles));
  EXPECT_TRUE(SameBytes(back.mesh.face_normals, made.mesh.face_normals));
  EXPECT_TRUE(SameBytes(back.mesh.triangle_part, made.mesh.triangle_part));
  ASSERT_EQ(back.mesh.parts.size(), made.mesh.parts.size());
  for (std::size_t i = 0; i < made.mesh.parts.size(); ++i) {
    EXPECT_EQ(back.mesh.parts[i].name, made.mesh.parts[i].name);
    EXPECT_EQ(back.mesh.parts[i].tooth_number, made.mesh.parts[i].tooth_number);
  }
  EXPECT_TRUE(SameBytes(back.source_vertex, made.source_vertex));
  EXPECT_EQ(std::memcmp(&back.cell_mm, &made.cell_mm, sizeof(double)), 0);
  EXPECT_EQ(std::memcmp(&back.error_bound_mm, &made.error_bound_mm, sizeof(double)), 0);
}

TEST(DisplayDecimationTest, MalformedBytesOrAnotherMeshThrow) {
  const TriangleMesh mesh = MakeSyntheticJawPair({20000, 3}).upper_U;
  const DecimationResult made = DecimateForDisplay(mesh, {6000});
  const std::string good = EncodeDecimation(made);
  std::string version = good;
  version[0] = 9;
  std::string vertex = good;  // the first kept vertex's index, out of the mesh
  const std::int32_t far = 1 << 30;
  std::memcpy(vertex.data() + 40, &far, 4);
  std::string corner = good;  // the first triangle's first corner, beyond the kept vertices
  const std::int32_t beyond = static_cast<std::int32_t>(made.source_vertex.size());
  std::memcpy(corner.data() + 40 + 4 * made.source_vertex.size(), &beyond, 4);
  std::string part = good;  // the last triangle's part, beyond the parts
  const std::int32_t parts = static_cast<std::int32_t>(mesh.parts.size());
  std::memcpy(part.data() + good.size() - 4, &parts, 4);
  for (const std::string& bytes :
       {std::string(), good.substr(0, 39), good.substr(0, good.size() - 1), good + "x", version,
        vertex, corner, part}) {
    EXPECT_THROW(DecodeDecimation(bytes, mesh), std::runtime_error) << bytes.size();
  }
  // An empty result (of an empty mesh) round-trips too.
  const DecimationResult empty =
      DecodeDecimation(EncodeDecimation(DecimationResult{}), TriangleMesh{});
  EXPECT_TRUE(empty.mesh.empty());
  EXPECT_TRUE(empty.source_vertex.empty());
  // The bytes of one mesh for a smaller one: its kept vertices are not all there.
  const TriangleMesh other = test::MakeBox(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  EXPECT_THROW(DecodeDecimation(good, other), std::runtime_error);
}

TEST(DisplayDecimationTest, TheKeyFollowsTheMeshAndTheBudget) {
  const TriangleMesh mesh = MakeSyntheticJawPair({20000, 3}).upper_U;
  const std::uint64_t key = DecimationKey(mesh, {6000});
  EXPECT_EQ(key, DecimationKey(TriangleMesh(mesh), {6000}));
  EXPECT_NE(key, DecimationKey(mesh, {6001}));
  TriangleMesh moved = mesh;
  moved.vertices[3].z() = std::nextafter(moved.vertices[3].z(), 1e9);
  EXPECT_NE(key, DecimationKey(moved, {6000}));
}

}  // namespace
}  // namespace occlude::io
