// Tests of the procedural synthetic jaw pair: option validation, closed outward edge-manifold
// meshes within the triangle budget, no self-intersection, the ground-truth bite (no
// interpenetration, real contacts on both sides), plausible arch dimensions, tooth parts and
// determinism. Distances are measured by brute force (closest point on triangles near each
// vertex, found through a uniform grid), independently of the generator's construction.
#include "occlude/io/synthetic_jaws.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "occlude/collision/closest_point.h"
#include "occlude/io/dental.h"

namespace occlude::io {
namespace {

// Named tolerances (mm unless stated).
constexpr double kContactTolerance = kSyntheticContactToleranceMm;  // the generator's contract
constexpr double kBudgetTolerance = 0.10;                           // relative triangle count
constexpr double kMinTriangleArea = 1e-6;                           // mm^2: not degenerate
constexpr double kPullApart = 0.5;        // open the bite this far along the occlusal axis ...
constexpr double kMinOpening = 0.36;      // ... and the jaws must be at least this far apart
constexpr double kPushTogether = 0.2;     // close the bite this far ...
constexpr double kMinBiteThrough = 0.15;  // ... and some point must sink at least this deep
constexpr double kSearchRadius = 3.0;     // penetration search around each vertex
constexpr double kTieTolerance = 1e-9;    // closest-point distances equal up to rounding

SyntheticJawPair Make(std::size_t budget, std::uint32_t seed) {
  SyntheticJawOptions options;
  options.triangles_per_jaw = budget;
  options.seed = seed;
  return MakeSyntheticJawPair(options);
}

/// Make, remembering the pairs of the parameterised tests (generation is slow under the
/// sanitizers; the determinism test calls Make itself).
const SyntheticJawPair& Cached(std::size_t budget, std::uint32_t seed) {
  static std::map<std::pair<std::size_t, std::uint32_t>, SyntheticJawPair> cache;
  auto it = cache.find({budget, seed});
  if (it == cache.end()) it = cache.emplace(std::make_pair(budget, seed), Make(budget, seed)).first;
  return it->second;
}

/// The upper jaw in L at the bite moved by `offset` mm along the occlusal axis (> 0 opens).
TriangleMesh UpperInL(const SyntheticJawPair& pair, double offset) {
  return pair.upper_U.Transformed(Eigen::Translation3d(offset * pair.occlusal_axis_L) * pair.X_LU);
}

// ------------------------------------------------------------------------ topology helpers

/// Number of directed edges that do not appear exactly once with their reverse exactly once
/// (0 for a closed, edge-manifold, consistently oriented surface).
std::size_t BadDirectedEdges(const TriangleMesh& mesh) {
  std::unordered_map<std::uint64_t, int> count;
  const auto key = [](int a, int b) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
           static_cast<std::uint32_t>(b);
  };
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++count[key(tri[k], tri[(k + 1) % 3])];
  }
  std::size_t bad = 0;
  for (const auto& [edge, n] : count) {
    const auto a = static_cast<int>(edge >> 32);
    const auto b = static_cast<int>(edge & 0xffffffffu);
    const auto reverse = count.find(key(b, a));
    if (n != 1 || reverse == count.end() || reverse->second != 1) ++bad;
  }
  return bad;
}

/// Enclosed volume by the divergence theorem, mm^3 (> 0 for an outward closed surface).
double EnclosedVolume(const TriangleMesh& mesh) {
  double six_volume = 0.0;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    six_volume += mesh.corner(t, 0).dot(mesh.corner(t, 1).cross(mesh.corner(t, 2)));
  }
  return six_volume / 6.0;
}

// --------------------------------------------------------------------- proximity helpers

/// Triangles binned by their bounding boxes in a uniform grid (cell mm, cells indexed within
/// +-4096 of the origin), for local queries.
class TriangleBins {
 public:
  TriangleBins(const TriangleMesh& mesh, double cell) : cell_(cell) {
    stamp_.assign(mesh.num_triangles(), 0);
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      Eigen::AlignedBox3d box(mesh.corner(t, 0));
      box.extend(mesh.corner(t, 1));
      box.extend(mesh.corner(t, 2));
      ForCells(box, [&](std::int64_t k) { bins_[k].push_back(static_cast<int>(t)); });
    }
  }

  /// Calls visit(t) once for every triangle whose bounding box may meet `box`.
  template <typename Visit>
  void ForTriangles(const Eigen::AlignedBox3d& box, Visit visit) {
    ++query_;
    ForCells(box, [&](std::int64_t k) {
      const auto it = bins_.find(k);
      if (it == bins_.end()) return;
      for (const int t : it->second) {
        if (stamp_[static_cast<std::size_t>(t)] == query_) continue;
        stamp_[static_cast<std::size_t>(t)] = query_;
        visit(t);
      }
    });
  }

 private:
  template <typename F>
  void ForCells(const Eigen::AlignedBox3d& box, F f) const {
    const Eigen::Vector3i lo = (box.min() / cell_).array().floor().cast<int>();
    const Eigen::Vector3i hi = (box.max() / cell_).array().floor().cast<int>();
    for (int x = lo.x(); x <= hi.x(); ++x) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int z = lo.z(); z <= hi.z(); ++z) {
          f((static_cast<std::int64_t>(x + 4096) << 26) |
            (static_cast<std::int64_t>(y + 4096) << 13) | static_cast<std::int64_t>(z + 4096));
        }
      }
    }
  }

  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> bins_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t query_ = 0;
};

/// Distance from p to a mesh, signed by the face normal (< 0: inside), searching `radius`.
struct MeshDistance {
  bool found = false;     ///< a triangle lies within the radius
  double distance = 0.0;  ///< unsigned, mm
  double signed_distance = 0.0;
  int triangle = -1;
};

/// Signs by the candidate triangle (among those at the minimal distance) whose normal is most
/// aligned with p - q: robust at convex and concave edges and vertices.
MeshDistance DistanceToMesh(const TriangleMesh& mesh, TriangleBins& bins, const Eigen::Vector3d& p,
                            double radius) {
  MeshDistance best;
  double best_alignment = -1.0;
  const Eigen::AlignedBox3d box(p - Eigen::Vector3d::Constant(radius),
                                p + Eigen::Vector3d::Constant(radius));
  bins.ForTriangles(box, [&](int t) {
    const auto ut = static_cast<std::size_t>(t);
    const auto cp = collision::ClosestPointOnTriangle(p, mesh.corner(ut, 0), mesh.corner(ut, 1),
                                                      mesh.corner(ut, 2));
    const double d = std::sqrt(cp.squared_distance);
    if (d > radius) return;
    const Eigen::Vector3d away = p - cp.point;
    const double alignment = d > 0.0 ? away.dot(mesh.face_normals[ut]) / d : 0.0;
    if (!best.found || d < best.distance - kTieTolerance) {
      best = {true, d, alignment < 0.0 ? -d : d, t};
      best_alignment = alignment;
    } else if (std::abs(d - best.distance) <= kTieTolerance &&
               std::abs(alignment) > std::abs(best_alignment)) {
      best.distance = std::min(d, best.distance);
      best.signed_distance = alignment < 0.0 ? -best.distance : best.distance;
      best.triangle = t;
      best_alignment = alignment;
    }
  });
  return best;
}

/// DistanceToMesh with growing search radii up to max_radius: the first radius that finds a
/// triangle finds the nearest one.
MeshDistance NearestOnMesh(const TriangleMesh& mesh, TriangleBins& bins, const Eigen::Vector3d& p,
                           double max_radius) {
  for (double radius = 0.5;; radius *= 3.0) {
    const MeshDistance d = DistanceToMesh(mesh, bins, p, std::min(radius, max_radius));
    if (d.found || radius >= max_radius) return d;
  }
}

/// Inside test by ray parity (brute force), along a direction no mesh edge or face is
/// parallel to.
bool InsideByParity(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  const Eigen::Vector3d dir = Eigen::Vector3d(0.0123, 1.0, 0.0371).normalized();
  int crossings = 0;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {  // Moller-Trumbore
    const Eigen::Vector3d e1 = mesh.corner(t, 1) - mesh.corner(t, 0);
    const Eigen::Vector3d e2 = mesh.corner(t, 2) - mesh.corner(t, 0);
    const Eigen::Vector3d h = dir.cross(e2);
    const double det = e1.dot(h);
    if (det == 0.0) continue;
    const Eigen::Vector3d s = p - mesh.corner(t, 0);
    const double u = s.dot(h) / det;
    const Eigen::Vector3d q = s.cross(e1);
    const double v = dir.dot(q) / det;
    if (u < 0.0 || v < 0.0 || u + v > 1.0) continue;
    if (e2.dot(q) / det > 0.0) ++crossings;
  }
  return crossings % 2 == 1;
}

/// Deepest point (vertex) of `a` inside `b`, mm (0 when none is inside). A vertex with no
/// surface of b within kSearchRadius that is inside b counts as kSearchRadius deep.
double MaxPenetration(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleBins bins(b, 1.0);
  const Eigen::AlignedBox3d b_box = b.Bounds();
  double deepest = 0.0;
  for (const Eigen::Vector3d& p : a.vertices) {
    if (!b_box.contains(p)) continue;  // outside b's bounding box: not inside b
    const MeshDistance d = NearestOnMesh(b, bins, p, kSearchRadius);
    if (d.found) {
      deepest = std::max(deepest, -d.signed_distance);
    } else if (InsideByParity(b, p)) {
      deepest = std::max(deepest, kSearchRadius);
    }
  }
  return deepest;
}

/// Smallest distance from a vertex of `a` to `b` (capped at `radius`).
double MinVertexDistance(const TriangleMesh& a, const TriangleMesh& b, double radius) {
  TriangleBins bins(b, 1.0);
  double nearest = radius;
  for (const Eigen::Vector3d& p : a.vertices) {
    const MeshDistance d = DistanceToMesh(b, bins, p, radius);
    if (d.found) nearest = std::min(nearest, d.distance);
  }
  return nearest;
}

/// Part tooth numbers of the triangles of `mesh` within `radius` of p.
std::set<int> TeethNear(const TriangleMesh& mesh, const Eigen::Vector3d& p, double radius) {
  std::set<int> teeth;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto cp = collision::ClosestPointOnTriangle(p, mesh.corner(t, 0), mesh.corner(t, 1),
                                                      mesh.corner(t, 2));
    if (cp.squared_distance <= radius * radius) {
      teeth.insert(mesh.parts[static_cast<std::size_t>(mesh.triangle_part[t])].tooth_number);
    }
  }
  return teeth;
}

// ------------------------------------------------------------------------------ options

TEST(SyntheticJawsTest, RejectsBudgetsOutsideTheValidRange) {
  for (const std::size_t budget :
       {std::size_t{0}, kMinSyntheticTriangles - 1, kMaxSyntheticTriangles + 1}) {
    try {
      Make(budget, 1);
      ADD_FAILURE() << "budget " << budget << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("triangles_per_jaw"), std::string::npos) << e.what();
    }
  }
}

TEST(SyntheticJawsTest, TriangleCountsMeetTheBudget) {
  for (const std::size_t budget :
       {kMinSyntheticTriangles, std::size_t{20000}, std::size_t{100000}, kMaxSyntheticTriangles}) {
    const SyntheticJawPair pair = Make(budget, 1);
    for (const TriangleMesh* mesh : {&pair.lower_L, &pair.upper_U}) {
      const auto n = static_cast<double>(mesh->num_triangles());
      EXPECT_LE(std::abs(n - static_cast<double>(budget)), kBudgetTolerance * budget)
          << mesh->num_triangles() << " triangles for a budget of " << budget;
    }
  }
}

TEST(SyntheticJawsTest, SameOptionsGiveIdenticalPairsAndSeedsDiffer) {
  const SyntheticJawPair a = Make(20000, 3);
  const SyntheticJawPair b = Make(20000, 3);
  EXPECT_EQ(a.lower_L.vertices, b.lower_L.vertices);
  EXPECT_EQ(a.upper_U.vertices, b.upper_U.vertices);
  EXPECT_EQ(a.lower_L.triangles, b.lower_L.triangles);
  EXPECT_EQ(a.upper_U.triangles, b.upper_U.triangles);
  EXPECT_EQ(a.lower_L.triangle_part, b.lower_L.triangle_part);
  EXPECT_EQ(a.upper_U.triangle_part, b.upper_U.triangle_part);
  EXPECT_TRUE(a.X_LU.matrix() == b.X_LU.matrix());
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  for (std::size_t i = 0; i < a.contacts.size(); ++i) {
    EXPECT_EQ(a.contacts[i].p_L, b.contacts[i].p_L);
    EXPECT_EQ(a.contacts[i].upper_tooth, b.contacts[i].upper_tooth);
  }
  const SyntheticJawPair c = Make(20000, 4);
  EXPECT_NE(a.lower_L.vertices, c.lower_L.vertices);
}

// ------------------------------------------------------------------------- per pair

class SyntheticPairTest : public ::testing::TestWithParam<std::tuple<std::size_t, std::uint32_t>> {
 protected:
  SyntheticPairTest()
      : budget_(std::get<0>(GetParam())), pair_(Cached(budget_, std::get<1>(GetParam()))) {}
  const std::size_t budget_;
  const SyntheticJawPair& pair_;
};

TEST_P(SyntheticPairTest, BothJawsAreClosedOutwardEdgeManifolds) {
  for (const TriangleMesh* mesh : {&pair_.lower_L, &pair_.upper_U}) {
    EXPECT_EQ(mesh->ConsistencyError(), "");
    EXPECT_EQ(BadDirectedEdges(*mesh), 0u);
    EXPECT_GT(EnclosedVolume(*mesh), 0.0);
    std::size_t degenerate = 0;
    for (std::size_t t = 0; t < mesh->num_triangles(); ++t) {
      const Eigen::Vector3i& tri = mesh->triangles[t];
      const double area = 0.5 * (mesh->corner(t, 1) - mesh->corner(t, 0))
                                    .cross(mesh->corner(t, 2) - mesh->corner(t, 0))
                                    .norm();
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || area < kMinTriangleArea) {
        ++degenerate;
      }
    }
    EXPECT_EQ(degenerate, 0u);
  }
}

TEST_P(SyntheticPairTest, NothingInterpenetratesAtTheBite) {
  const TriangleMesh upper_L = UpperInL(pair_, 0.0);
  EXPECT_LE(MaxPenetration(upper_L, pair_.lower_L), kContactTolerance);
  EXPECT_LE(MaxPenetration(pair_.lower_L, upper_L), kContactTolerance);
}

TEST_P(SyntheticPairTest, ContactsTouchBothSurfacesOnBothSidesAndOnMolars) {
  const TriangleMesh upper_L = UpperInL(pair_, 0.0);
  TriangleBins lower_bins(pair_.lower_L, 1.0);
  TriangleBins upper_bins(upper_L, 1.0);
  bool left = false, right = false, left_molar = false, right_molar = false;
  for (const SyntheticContact& c : pair_.contacts) {
    const MeshDistance to_lower = DistanceToMesh(pair_.lower_L, lower_bins, c.p_L, 1.0);
    const MeshDistance to_upper = DistanceToMesh(upper_L, upper_bins, c.p_L, 1.0);
    EXPECT_TRUE(to_lower.found && to_lower.distance <= kContactTolerance) << to_lower.distance;
    EXPECT_TRUE(to_upper.found && to_upper.distance <= kContactTolerance) << to_upper.distance;
    EXPECT_GE(c.upper_tooth, 1);
    EXPECT_LE(c.upper_tooth, 16);
    EXPECT_GE(c.lower_tooth, 17);
    EXPECT_LE(c.lower_tooth, 32);
    const bool molar = c.lower_tooth <= 19 || c.lower_tooth >= 30;
    (c.p_L.x() > 0.0 ? left : right) = true;  // +x is the patient's left
    if (molar) (c.p_L.x() > 0.0 ? left_molar : right_molar) = true;
  }
  EXPECT_TRUE(left && right) << pair_.contacts.size() << " contacts";
  EXPECT_TRUE(left_molar && right_molar);
}

TEST_P(SyntheticPairTest, OpeningTheBiteSeparatesTheJaws) {
  const TriangleMesh upper_L = UpperInL(pair_, kPullApart);
  EXPECT_GE(MinVertexDistance(upper_L, pair_.lower_L, kPullApart), kMinOpening);
  EXPECT_GE(MinVertexDistance(pair_.lower_L, upper_L, kPullApart), kMinOpening);
}

TEST_P(SyntheticPairTest, ClosingTheBiteFurtherInterpenetrates) {
  const TriangleMesh upper_L = UpperInL(pair_, -kPushTogether);
  const double depth =
      std::max(MaxPenetration(upper_L, pair_.lower_L), MaxPenetration(pair_.lower_L, upper_L));
  EXPECT_GE(depth, kMinBiteThrough);
  EXPECT_LE(depth, kPushTogether + kContactTolerance);
}

TEST_P(SyntheticPairTest, PartsNumberEveryToothAndCoverTheCrowns) {
  const TriangleMesh upper_L = UpperInL(pair_, 0.0);
  for (const bool upper : {true, false}) {
    const TriangleMesh& mesh = upper ? upper_L : pair_.lower_L;
    std::set<int> expected = {0};
    for (int n = upper ? 2 : 18; n <= (upper ? 15 : 31); ++n) expected.insert(n);
    std::set<int> named, used;
    for (const MeshPart& part : mesh.parts) named.insert(part.tooth_number);
    for (const std::int32_t p : mesh.triangle_part) {
      used.insert(mesh.parts[static_cast<std::size_t>(p)].tooth_number);
    }
    EXPECT_EQ(named, expected);
    EXPECT_EQ(used, expected);
    // Everything within 2.5 mm of the occlusal extreme is crown: the gingiva lies >= 5 mm away.
    constexpr double kCrownBand = 2.5;
    const double extreme = upper ? mesh.Bounds().min().y() : mesh.Bounds().max().y();
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      bool in_band = true;
      for (int k = 0; k < 3; ++k) in_band &= std::abs(mesh.corner(t, k).y() - extreme) < kCrownBand;
      if (in_band) {
        EXPECT_NE(mesh.parts[static_cast<std::size_t>(mesh.triangle_part[t])].tooth_number, 0)
            << (upper ? "upper" : "lower") << " triangle " << t;
      }
    }
  }
  if (budget_ > 5000) return;  // the brute-force part lookup below is quadratic
  for (const SyntheticContact& c : pair_.contacts) {
    EXPECT_EQ(TeethNear(upper_L, c.p_L, kContactTolerance).count(c.upper_tooth), 1u);
    EXPECT_EQ(TeethNear(pair_.lower_L, c.p_L, kContactTolerance).count(c.lower_tooth), 1u);
  }
}

TEST_P(SyntheticPairTest, ArchDimensionsArePlausible) {
  // Lower molar crowns 50-55 mm apart buccally, arch 40-50 mm deep (with some slack).
  Eigen::AlignedBox3d molars, teeth;
  for (std::size_t t = 0; t < pair_.lower_L.num_triangles(); ++t) {
    const int n =
        pair_.lower_L.parts[static_cast<std::size_t>(pair_.lower_L.triangle_part[t])].tooth_number;
    if (n == 0) continue;
    for (int k = 0; k < 3; ++k) {
      teeth.extend(pair_.lower_L.corner(t, k));
      if (n == 19 || n == 30) molars.extend(pair_.lower_L.corner(t, k));
    }
  }
  EXPECT_GT(molars.sizes().x(), 48.0);
  EXPECT_LT(molars.sizes().x(), 58.0);
  EXPECT_GT(teeth.sizes().z(), 40.0);
  EXPECT_LT(teeth.sizes().z(), 50.0);
  EXPECT_DOUBLE_EQ(pair_.occlusal_axis_L.norm(), 1.0);
  EXPECT_GT(UpperInL(pair_, 0.0).Bounds().center().y(), pair_.lower_L.Bounds().center().y());
}

// ---------------------------------------------------------------------------- landmarks

/// A landmark in L at the bite (upper ones moved by X_LU).
Eigen::Vector3d AtBite(const SyntheticJawPair& pair, const Landmark& l) {
  return l.jaw == Jaw::kUpper ? Eigen::Vector3d(pair.X_LU * l.p) : l.p;
}

/// The types clinical.md gives a tooth at this FDI position.
std::set<LandmarkType> ExpectedTypes(Jaw jaw, int fdi) {
  using LT = LandmarkType;
  std::set<LT> types = {LT::kMesial, LT::kDistal, LT::kFacial, LT::kLingual};
  const int position = ToothPosition(fdi);
  if (position <= 2) types.insert(LT::kIncisalEdge);
  if (position == 3) types.insert(LT::kCuspTip);
  if (position == 4 || position == 5) {
    types.insert({LT::kBuccalCusp, LT::kLingualCusp, LT::kCentralFossa});
  }
  if (position >= 6) {
    types.insert({LT::kMbCusp, LT::kDbCusp, LT::kMlCusp, LT::kDlCusp, LT::kCentralFossa});
  }
  if (position == 6 && jaw == Jaw::kLower) types.insert(LT::kMiddleBuccalCusp);
  return types;
}

bool IsOcclusalFeature(LandmarkType type) {
  return type != LandmarkType::kMesial && type != LandmarkType::kDistal &&
         type != LandmarkType::kFacial && type != LandmarkType::kLingual;
}

TEST_P(SyntheticPairTest, EveryToothCarriesTheLandmarksOfItsType) {
  std::map<std::pair<Jaw, int>, std::multiset<LandmarkType>> found;
  for (const Landmark& l : pair_.landmarks) {
    ASSERT_TRUE(IsValidFdi(l.tooth_fdi)) << l.tooth_fdi;
    EXPECT_EQ(JawOfFdi(l.tooth_fdi), l.jaw) << l.tooth_fdi;
    EXPECT_TRUE(l.p.allFinite());
    found[{l.jaw, l.tooth_fdi}].insert(l.type);
  }
  EXPECT_EQ(found.size(), 28u);  // 7 teeth per quadrant, no third molars
  for (const int quadrant : {1, 2, 3, 4}) {
    for (int position = 1; position <= 7; ++position) {
      const int fdi = 10 * quadrant + position;
      const Jaw jaw = JawOfFdi(fdi);
      const std::set<LandmarkType> expected = ExpectedTypes(jaw, fdi);
      const std::multiset<LandmarkType>& got = found[{jaw, fdi}];
      EXPECT_EQ(got.size(), expected.size()) << "tooth " << fdi << ": a type twice or missing";
      EXPECT_EQ(std::set<LandmarkType>(got.begin(), got.end()), expected) << "tooth " << fdi;
    }
  }
}

TEST_P(SyntheticPairTest, LandmarksLieOnTheFinalSurfacesOfTheirTeeth) {
  // Upper landmarks are in U, like upper_U; each must be a point of its jaw's mesh, and the
  // occlusal features (edges, cusps, fossae) on a triangle of their own tooth's part.
  constexpr double kOnSurface = 1e-9;  // mm: a convex combination of a triangle's corners
  TriangleBins lower_bins(pair_.lower_L, 1.0);
  TriangleBins upper_bins(pair_.upper_U, 1.0);
  for (const Landmark& l : pair_.landmarks) {
    const bool upper = l.jaw == Jaw::kUpper;
    const TriangleMesh& mesh = upper ? pair_.upper_U : pair_.lower_L;
    const MeshDistance d = DistanceToMesh(mesh, upper ? upper_bins : lower_bins, l.p, 1.0);
    ASSERT_TRUE(d.found) << l.tooth_fdi << " " << ToString(l.type);
    EXPECT_LE(d.distance, kOnSurface) << l.tooth_fdi << " " << ToString(l.type);
    if (!IsOcclusalFeature(l.type)) continue;
    const int part_tooth = mesh.parts[static_cast<std::size_t>(
                                          mesh.triangle_part[static_cast<std::size_t>(d.triangle)])]
                               .tooth_number;
    EXPECT_EQ(part_tooth, UniversalFromFdi(l.tooth_fdi)) << l.tooth_fdi << " " << ToString(l.type);
  }
}

/// The landmark of a tooth and type (ADD_FAILURE and the origin when missing).
Eigen::Vector3d Find(const SyntheticJawPair& pair, int fdi, LandmarkType type) {
  for (const Landmark& l : pair.landmarks) {
    if (l.tooth_fdi == fdi && l.type == type) return AtBite(pair, l);
  }
  ADD_FAILURE() << "no " << ToString(type) << " on tooth " << fdi;
  return Eigen::Vector3d::Zero();
}

TEST_P(SyntheticPairTest, NeighboursShareTheirContactPoints) {
  // Along each quadrant the distal contact of a tooth is the mesial contact of the next; the
  // central incisors meet on the midline.
  for (const int quadrant : {1, 2, 3, 4}) {
    for (int position = 1; position < 7; ++position) {
      const int fdi = 10 * quadrant + position;
      EXPECT_LE(
          (Find(pair_, fdi, LandmarkType::kDistal) - Find(pair_, fdi + 1, LandmarkType::kMesial))
              .norm(),
          1e-9)
          << fdi;
    }
  }
  EXPECT_LE(
      (Find(pair_, 11, LandmarkType::kMesial) - Find(pair_, 21, LandmarkType::kMesial)).norm(),
      1e-9);
  EXPECT_LE(
      (Find(pair_, 41, LandmarkType::kMesial) - Find(pair_, 31, LandmarkType::kMesial)).norm(),
      1e-9);
}

/// Largest rise (towards the other jaw) of `mesh`'s occlusal vertices within `radius` of p in xz
/// above p itself, mm: <= 0 when p is the local extreme.
double RiseBeside(const TriangleMesh& mesh, const Eigen::Vector3d& p, double radius, bool upper) {
  double rise = -1e9;
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (std::hypot(v.x() - p.x(), v.z() - p.z()) > radius) continue;
    rise = std::max(rise, upper ? p.y() - v.y() : v.y() - p.y());
  }
  return rise;
}

TEST_P(SyntheticPairTest, CuspTipsAndIncisalEdgesAreTheOcclusalExtremesAroundThem) {
  // What a detector finds (the extreme along the occlusal axis near a cusp) is the landmark:
  // no vertex within kTipRadius stands out further towards the other jaw by more than
  // kTipTolerance (cusp tips are worn flat, so a plateau counts).
  constexpr double kTipRadius = 1.0;      // mm, in the occlusal plane
  constexpr double kTipTolerance = 0.05;  // mm
  const TriangleMesh upper_L = UpperInL(pair_, 0.0);
  using LT = LandmarkType;
  for (const Landmark& l : pair_.landmarks) {
    if (l.type == LT::kCentralFossa || !IsOcclusalFeature(l.type)) continue;
    const bool upper = l.jaw == Jaw::kUpper;
    EXPECT_LE(RiseBeside(upper ? upper_L : pair_.lower_L, AtBite(pair_, l), kTipRadius, upper),
              kTipTolerance)
        << ToString(l.jaw) << " " << l.tooth_fdi << " " << ToString(l.type);
  }
}

/// clinical.md's relationships computed here from the landmarks (independently of the
/// generator), in L's axes: occlusal +y, anterior +z, lateral +x.
SyntheticRelationships FromLandmarks(const SyntheticJawPair& pair, const Eigen::Vector3d& shift_L) {
  using LT = LandmarkType;
  const auto upper = [&](int fdi, LT type) -> Eigen::Vector3d {
    return Find(pair, fdi, type) + shift_L;
  };
  const auto lower = [&](int fdi, LT type) -> Eigen::Vector3d { return Find(pair, fdi, type); };
  const auto mesial_direction = [&](int fdi) {
    Eigen::Vector3d t = lower(fdi, LT::kMesial) - lower(fdi, LT::kDistal);
    t.y() = 0.0;
    return t.normalized();
  };
  SyntheticRelationships r;
  r.overjet_mm = 0.5 * (upper(11, LT::kIncisalEdge).z() - lower(41, LT::kIncisalEdge).z() +
                        upper(21, LT::kIncisalEdge).z() - lower(31, LT::kIncisalEdge).z());
  r.overbite_mm = 0.5 * (lower(41, LT::kIncisalEdge).y() - upper(11, LT::kIncisalEdge).y() +
                         lower(31, LT::kIncisalEdge).y() - upper(21, LT::kIncisalEdge).y());
  r.midline_deviation_mm = 0.5 * (upper(11, LT::kMesial).x() + upper(21, LT::kMesial).x()) -
                           0.5 * (lower(41, LT::kMesial).x() + lower(31, LT::kMesial).x());
  const auto molar = [&](int u, int l) {
    const Eigen::Vector3d groove = 0.5 * (lower(l, LT::kMbCusp) + lower(l, LT::kMiddleBuccalCusp));
    return (upper(u, LT::kMbCusp) - groove).dot(mesial_direction(l));
  };
  const auto canine = [&](int u, int l) {
    const Eigen::Vector3d embrasure = 0.5 * (lower(l, LT::kDistal) + lower(l + 1, LT::kMesial));
    return (upper(u, LT::kCuspTip) - embrasure).dot(mesial_direction(l));
  };
  r.molar_mm = {molar(16, 46), molar(26, 36)};
  r.canine_mm = {canine(13, 43), canine(23, 33)};
  return r;
}

TEST_P(SyntheticPairTest, DesignedBiteIsANormalClassOneOcclusion) {
  constexpr double kSameMeasure = 1e-9;  // mm: the same definitions on the same points
  // Molar and canine offsets: 0 by design; the tips are the meshes' most prominent vertices
  // there, within about half a grid cell (1 mm at 5,000 triangles, as 1 / sqrt(budget)).
  const double kClassOne = 0.6 * std::sqrt(5000.0 / static_cast<double>(budget_));
  constexpr double kMidline = 0.01;  // mm
  const SyntheticRelationships& r = pair_.relationships;
  const SyntheticRelationships mine = FromLandmarks(pair_, Eigen::Vector3d::Zero());
  EXPECT_NEAR(r.overjet_mm, mine.overjet_mm, kSameMeasure);
  EXPECT_NEAR(r.overbite_mm, mine.overbite_mm, kSameMeasure);
  EXPECT_NEAR(r.midline_deviation_mm, mine.midline_deviation_mm, kSameMeasure);
  EXPECT_NEAR(r.molar_mm.right, mine.molar_mm.right, kSameMeasure);
  EXPECT_NEAR(r.molar_mm.left, mine.molar_mm.left, kSameMeasure);
  EXPECT_NEAR(r.canine_mm.right, mine.canine_mm.right, kSameMeasure);
  EXPECT_NEAR(r.canine_mm.left, mine.canine_mm.left, kSameMeasure);
  // clinical.md's normal ranges: overjet and overbite 1-3 mm, Class I within 1.5 mm.
  EXPECT_GE(r.overjet_mm, 1.0);
  EXPECT_LE(r.overjet_mm, 3.0);
  EXPECT_GE(r.overbite_mm, 1.0);
  EXPECT_LE(r.overbite_mm, 3.0);
  EXPECT_LE(std::abs(r.midline_deviation_mm), kMidline);
  for (const double offset :
       {r.molar_mm.right, r.molar_mm.left, r.canine_mm.right, r.canine_mm.left}) {
    EXPECT_LE(std::abs(offset), kClassOne);
  }
}

TEST_P(SyntheticPairTest, TheClassTwoShiftMovesTheUpperMesiallyByIt) {
  // The relationships' signs: the upper moved along +z by the shift is upper mesial on both
  // sides (Class II) by the shift, with the overjet grown by it and the midline unchanged.
  const double shift = pair_.class2_shift_L.norm();
  EXPECT_GE(shift, 3.5);  // clinical.md: half a cusp to a premolar width
  EXPECT_LE(shift, 7.0);
  EXPECT_GT(pair_.class2_shift_L.z(), 0.99 * shift);
  const SyntheticRelationships at = FromLandmarks(pair_, Eigen::Vector3d::Zero());
  const SyntheticRelationships moved = FromLandmarks(pair_, pair_.class2_shift_L);
  constexpr double kAlongTheArch = 0.05;  // mm: the posterior segments run along z
  EXPECT_NEAR(moved.molar_mm.right - at.molar_mm.right, shift, kAlongTheArch);
  EXPECT_NEAR(moved.molar_mm.left - at.molar_mm.left, shift, kAlongTheArch);
  EXPECT_GT(moved.canine_mm.right - at.canine_mm.right, 1.5);  // Class II at the canines too
  EXPECT_GT(moved.canine_mm.left - at.canine_mm.left, 1.5);
  EXPECT_NEAR(moved.overjet_mm - at.overjet_mm, pair_.class2_shift_L.z(), 1e-9);
  EXPECT_NEAR(moved.midline_deviation_mm, at.midline_deviation_mm, 1e-9);
}

TEST_P(SyntheticPairTest, TheClassTwoAlternativeRestsOnTheLowerAndTouchesOnBothSides) {
  // At the alternative no vertex of one jaw lies deeper than kAlternativeDepth inside the other
  // (the vertices are checked by construction; between them the surfaces may cross a little),

  constexpr double kAlternativeDepth = 0.05;  // mm: the planner's default penetration limit
  constexpr double kTouch = 0.1;              // mm: the default contact band
  const TriangleMesh upper_L =
      pair_.upper_U.Transformed(Eigen::Translation3d(pair_.class2_shift_L) * pair_.X_LU);
  EXPECT_LE(MaxPenetration(upper_L, pair_.lower_L), kAlternativeDepth);
  EXPECT_LE(MaxPenetration(pair_.lower_L, upper_L), kAlternativeDepth);
  TriangleBins bins(pair_.lower_L, 1.0);
  double nearest[2] = {kTouch + 1.0, kTouch + 1.0};  // right, left
  for (std::size_t t = 0; t < upper_L.num_triangles(); ++t) {
    const int tooth =
        upper_L.parts[static_cast<std::size_t>(upper_L.triangle_part[t])].tooth_number;
    if (tooth == 0 || ToothPosition(FdiFromUniversal(tooth)) < 4) continue;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& p = upper_L.corner(t, k);
      const MeshDistance d = DistanceToMesh(pair_.lower_L, bins, p, 1.0);
      double& side = nearest[p.x() > 0.0 ? 1 : 0];
      if (d.found) side = std::min(side, d.distance);
    }
  }
  EXPECT_LE(nearest[0], kTouch) << "right";
  EXPECT_LE(nearest[1], kTouch) << "left";
}

INSTANTIATE_TEST_SUITE_P(
    SyntheticBudgetsAndSeeds, SyntheticPairTest,
    ::testing::Combine(::testing::Values(std::size_t{5000}, std::size_t{20000}),
                       ::testing::Values(1u, 2u, 7u)),
    [](const ::testing::TestParamInfo<SyntheticPairTest::ParamType>& param_info) {
      return "triangles" + std::to_string(std::get<0>(param_info.param)) + "_seed" +
             std::to_string(std::get<1>(param_info.param));
    });

// ------------------------------------------------------------------ self-intersection

/// Closed triangles A and B share a point (touching counts), by the separating axis theorem:
/// they are disjoint iff their projections are disjoint on one of the face normals, the nine
/// edge-edge cross products or the six in-plane edge normals (coplanar case). Projections
/// closer than a rounding bound count as overlapping, so the answer errs towards "intersect".
/// (Written here rather than taken from collision/triangle_triangle.h, whose coplanar branch
/// reports some far-apart coplanar pairs as intersecting.)
bool TrianglesShareAPoint(const std::array<Eigen::Vector3d, 3>& a,
                          const std::array<Eigen::Vector3d, 3>& b) {
  double scale = 0.0;
  for (const auto* tri : {&a, &b}) {
    for (const Eigen::Vector3d& v : *tri) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  }
  const auto separates = [&](const Eigen::Vector3d& axis) {
    const double length = axis.norm();
    if (length <= 1e-12 * scale * scale) return false;  // degenerate axis
    double a_lo = a[0].dot(axis), a_hi = a_lo, b_lo = b[0].dot(axis), b_hi = b_lo;
    for (int k = 1; k < 3; ++k) {
      a_lo = std::min(a_lo, a[k].dot(axis));
      a_hi = std::max(a_hi, a[k].dot(axis));
      b_lo = std::min(b_lo, b[k].dot(axis));
      b_hi = std::max(b_hi, b[k].dot(axis));
    }
    const double rounding = 64.0 * std::numeric_limits<double>::epsilon() * scale * length;
    return a_hi < b_lo - rounding || b_hi < a_lo - rounding;
  };
  std::array<Eigen::Vector3d, 3> ea, eb;
  for (int k = 0; k < 3; ++k) {
    ea[k] = a[(k + 1) % 3] - a[k];
    eb[k] = b[(k + 1) % 3] - b[k];
  }
  const Eigen::Vector3d na = ea[0].cross(ea[1]);
  const Eigen::Vector3d nb = eb[0].cross(eb[1]);
  if (separates(na) || separates(nb)) return false;
  for (int i = 0; i < 3; ++i) {
    if (separates(na.cross(ea[i])) || separates(nb.cross(eb[i]))) return false;
    for (int j = 0; j < 3; ++j) {
      if (separates(ea[i].cross(eb[j]))) return false;
    }
  }
  return true;
}

TEST(SyntheticJawsTest, SeparatingAxisTriangleTestAgreesWithSimpleCases) {
  using V = Eigen::Vector3d;
  const std::array<V, 3> t = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
  EXPECT_TRUE(TrianglesShareAPoint(t, {V(0.2, 0.2, -1), V(0.2, 0.2, 1), V(0.3, 0.1, 1)}));
  EXPECT_FALSE(TrianglesShareAPoint(t, {V(0.2, 0.2, 0.1), V(0.4, 0.2, 1), V(0.3, 0.1, 1)}));
  EXPECT_TRUE(TrianglesShareAPoint(t, {V(0.5, 0.5, 0), V(2, 2, 0), V(2, 0.5, 0)}));   // coplanar
  EXPECT_FALSE(TrianglesShareAPoint(t, {V(0.6, 0.6, 0), V(2, 2, 0), V(2, 0.6, 0)}));  // coplanar
  EXPECT_TRUE(TrianglesShareAPoint(t, {V(1, 0, 0), V(2, 0, -1), V(2, 0, 1)}));        // touch
  // Coplanar far-apart triangles whose projected edges are nearly collinear.
  EXPECT_FALSE(TrianglesShareAPoint({V(-17.493884909091364, -6, -14.538682564429198),
                                     V(-18.218409445386321, -6, -13.355538712548226),
                                     V(-17.304049085772526, -6, -13.529140917741405)},
                                    {V(-30.105094120365663, -6, -11.098710045036901),
                                     V(-31.019454479979458, -6, -10.925107839843722),
                                     V(-30.816331485049211, -6, -9.8661040604646129)}));
}

/// Pairs of triangles that share no vertex yet share a point.
std::size_t SelfIntersections(const TriangleMesh& mesh) {
  TriangleBins bins(mesh, 2.0);
  std::size_t hits = 0;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    Eigen::AlignedBox3d box(mesh.corner(t, 0));
    box.extend(mesh.corner(t, 1));
    box.extend(mesh.corner(t, 2));
    const Eigen::Vector3i& a = mesh.triangles[t];
    bins.ForTriangles(box, [&](int other) {
      const auto u = static_cast<std::size_t>(other);
      if (u <= t) return;
      const Eigen::Vector3i& b = mesh.triangles[u];
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          if (a[i] == b[j]) return;  // adjacent: shares a vertex
        }
      }
      if (TrianglesShareAPoint({mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)},
                               {mesh.corner(u, 0), mesh.corner(u, 1), mesh.corner(u, 2)})) {
        ++hits;
      }
    });
  }
  return hits;
}

TEST(SyntheticJawsTest, NoSelfIntersectionAtTheSmallestBudget) {
  for (const std::uint32_t seed : {1u, 2u}) {
    const SyntheticJawPair pair = Make(kMinSyntheticTriangles, seed);
    EXPECT_EQ(SelfIntersections(pair.lower_L), 0u) << "seed " << seed;
    EXPECT_EQ(SelfIntersections(pair.upper_U), 0u) << "seed " << seed;
  }
}

}  // namespace
}  // namespace occlude::io
