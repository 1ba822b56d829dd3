// The region of interest (region_of_interest.h) on the synthetic jaw pair, as generated (both
// jaws closed) and with the lower's flat base removed (an open lower, like a scan, which the
// selection may cut): the oracle built on the two sub-meshes answers like the one built on the
// whole jaws at seeded poses within the bounds (sub-voxel and exact levels, a fine field and the
// planner's wide coarse one), the selection drops a real share of the triangles (the base and
// the gingiva far from the bite) and keeps closed lower components whole, the displacement
// bound holds at every sampled pose, the reach grows with the bounds and the kept sets with it,
// huge bounds keep everything, and the cut borders are farther than the reach from the other
// jaw (the open-border contract).
#include "occlude/collision/region_of_interest.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <set>

#include "occlude/angles.h"
#include "occlude/collision/signed_distance.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;

struct Scene {
  std::shared_ptr<const io::TriangleMesh> lower, upper;
  Isometry3d X_bite = Isometry3d::Identity();
  ArchFrame arch;
};

/// `mesh` without its triangles facing down (-y, the synthetic jaw's flat base): open.
io::TriangleMesh WithoutBase(const io::TriangleMesh& mesh) {
  io::TriangleMesh open = mesh;
  open.triangles.clear();
  open.triangle_part.clear();
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const Vector3d n =
        (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
    if (n.y() < -0.9 * n.norm()) continue;
    open.triangles.push_back(mesh.triangles[t]);
    open.triangle_part.push_back(mesh.triangle_part[t]);
  }
  open.ComputeFaceNormals();  // unused vertices stay: harmless
  return open;
}

/// The synthetic pair at 20,000 triangles per jaw (seed 3); `open_lower`: base removed.
const Scene& Synthetic(bool open_lower = false) {
  static const Scene closed = [] {
    io::SyntheticJawOptions options;
    options.triangles_per_jaw = 20000;
    options.seed = 3;
    io::SyntheticJawPair pair = io::MakeSyntheticJawPair(options);
    Scene s;
    s.X_bite = pair.X_LU;
    s.arch = EstimateArchFrame(pair.lower_L, pair.upper_U.Transformed(pair.X_LU));
    s.lower = std::make_shared<io::TriangleMesh>(std::move(pair.lower_L));
    s.upper = std::make_shared<io::TriangleMesh>(std::move(pair.upper_U));
    return s;
  }();
  static const Scene open = [] {
    Scene s = closed;
    s.lower = std::make_shared<io::TriangleMesh>(WithoutBase(*closed.lower));
    return s;
  }();
  return open_lower ? open : closed;
}

RegionOfInterestRequest Request(const Scene& s, double t_mm, double r_deg, double band_mm) {
  RegionOfInterestRequest r;
  r.X_LU_start = s.X_bite;
  r.pivot_L = s.X_bite.translation();  // U's origin: the centre of the upper occlusal surface
  for (std::size_t d = 0; d < 6; ++d) {
    const double m = d < 3 ? t_mm : r_deg;
    r.bound_min[d] = -m;
    r.bound_max[d] = m;
  }
  r.band_mm = band_mm;
  return r;
}

/// A seeded pose uniformly within the request's bounds (planner::ComposePose's convention).
Isometry3d PoseWithin(const RegionOfInterestRequest& r, std::mt19937* rng) {
  Vector3d t, w;
  for (int i = 0; i < 3; ++i) {
    t[i] = std::uniform_real_distribution<double>(r.bound_min[i], r.bound_max[i])(*rng);
    w[i] = std::uniform_real_distribution<double>(r.bound_min[i + 3], r.bound_max[i + 3])(*rng);
  }
  const double angle = RadiansFromDegrees(w.norm());
  const Eigen::Matrix3d R = angle > 0 ? Eigen::AngleAxisd(angle, w.normalized()).toRotationMatrix()
                                      : Eigen::Matrix3d::Identity();
  Isometry3d M = Isometry3d::Identity();
  M.linear() = R;
  M.translation() = r.pivot_L + t - R * r.pivot_L;
  return M * r.X_LU_start;
}

void ExpectSamePoints(const std::vector<SurfacePoint>& a, const std::vector<SurfacePoint>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].p_L, b[i].p_L) << i;
    EXPECT_EQ(a[i].distance_mm, b[i].distance_mm) << i;
    EXPECT_EQ(a[i].area_mm2, b[i].area_mm2) << i;
    EXPECT_EQ(a[i].part, b[i].part) << i;
  }
}

/// The sub-meshes share the whole meshes' grid frames (RegionMesh), so the kept samples are
/// the same floats in the same cells and order, and the fields read the same triangles: the
/// answers are expected equal to the last bit (no tolerance). The minimum distance is exact
/// within the band only (beyond it culling, which reads the cut jaws' distance bounds, leaves
/// an upper bound).
void ExpectSameAnswers(const OracleResult& whole, const OracleResult& roi, double band_mm,
                       const std::string& where) {
  SCOPED_TRACE(where);
  EXPECT_EQ(roi.contact_area_mm2, whole.contact_area_mm2);
  EXPECT_EQ(roi.contact_samples, whole.contact_samples);
  EXPECT_EQ(roi.penetration_area_mm2, whole.penetration_area_mm2);
  EXPECT_EQ(roi.max_penetration_mm, whole.max_penetration_mm);
  EXPECT_EQ(roi.deepest_p_L, whole.deepest_p_L);
  EXPECT_EQ(roi.deep_samples, whole.deep_samples);
  EXPECT_EQ(roi.left_share, whole.left_share);
  EXPECT_EQ(roi.anterior_share, whole.anterior_share);
  if (whole.min_distance_mm <= band_mm || roi.min_distance_mm <= band_mm) {
    EXPECT_EQ(roi.min_distance_mm, whole.min_distance_mm);
  }
  ASSERT_EQ(roi.parts.size(), whole.parts.size());
  for (std::size_t p = 0; p < whole.parts.size(); ++p) {
    EXPECT_EQ(roi.parts[p].tooth_number, whole.parts[p].tooth_number) << p;
    EXPECT_EQ(roi.parts[p].contact_area_mm2, whole.parts[p].contact_area_mm2) << "part " << p;
    EXPECT_EQ(roi.parts[p].penetration_area_mm2, whole.parts[p].penetration_area_mm2)
        << "part " << p;
    EXPECT_EQ(roi.parts[p].max_penetration_mm, whole.parts[p].max_penetration_mm) << "part " << p;
  }
  ExpectSamePoints(whole.contacts, roi.contacts);
  ExpectSamePoints(whole.penetrations, roi.penetrations);
  ASSERT_EQ(roi.residuals.size(), whole.residuals.size());
  for (std::size_t i = 0; i < whole.residuals.size(); ++i) {
    EXPECT_EQ(roi.residuals[i].distance_mm, whole.residuals[i].distance_mm) << i;
    EXPECT_EQ(roi.residuals[i].gradient, whole.residuals[i].gradient) << i;
  }
}

/// Builds whole and ROI oracles with `options` and compares them at seeded poses within the
/// bounds, at the sub-voxel and exact levels; returns how many poses had contact.
int CompareOracles(const Scene& s, const RegionOfInterestRequest& base, OracleOptions options,
                   int poses, std::uint32_t seed) {
  options.arch = s.arch;  // the whole jaws' frame, as CaseSession passes it
  OracleRequest query;
  query.contact_band_mm = 0.1;
  query.penetration_search_mm = 0.3;
  query.residuals = true;  // the planner's least squares read them (band 0.5 mm)
  RegionOfInterestRequest request = base;
  request.band_mm = OracleReadRadiusMm(
      options,
      std::max({query.contact_band_mm, query.penetration_search_mm, query.residual_band_mm}));
  const RegionOfInterest roi = ComputeRegionOfInterest(s.lower, s.upper, request);
  EXPECT_LT(roi.stats.upper_kept, roi.stats.upper_total);
  std::cout << "[ roi      ] kept " << roi.stats.lower_kept << " / " << roi.stats.lower_total
            << " lower, " << roi.stats.upper_kept << " / " << roi.stats.upper_total
            << " upper triangles, reach " << roi.stats.reach_mm << " mm\n";
  const JawOracle whole(s.lower, s.upper, options);
  const JawOracle cut(roi.lower.mesh, roi.upper.mesh, options);
  std::mt19937 rng(seed);
  int touching = 0;
  for (int i = 0; i < poses; ++i) {
    const Isometry3d X = PoseWithin(request, &rng);
    EXPECT_TRUE(RegionCoversPose(*s.upper, request.X_LU_start, X, roi.stats.displacement_mm));
    for (const AccuracyLevel level : {AccuracyLevel::kSubVoxel, AccuracyLevel::kExact}) {
      query.level = level;
      OracleResult a, b;
      whole.Query(X, query, &a);
      cut.Query(X, query, &b);
      ExpectSameAnswers(a, b, query.contact_band_mm,
                        "pose " + std::to_string(i) + " level " + ToString(level));
      if (level == AccuracyLevel::kSubVoxel && a.contact_area_mm2 > 0) ++touching;
    }
  }
  return touching;
}

TEST(RegionOfInterest, SameAnswersAsTheWholeJawsNearTheBite) {
  // Small bounds about the bite: most poses touch or interpenetrate (deeply, too).
  OracleOptions options;
  options.voxel_size_mm = 0.4;
  for (const bool open : {true, false}) {
    SCOPED_TRACE(open ? "open lower" : "closed lower");
    const Scene& s = Synthetic(open);
#ifdef OCCLUDE_SANITIZED
    constexpr int kComparedPoses =
        8;  // the sanitizer lane looks for memory errors (the release lane: 16)
#else
    constexpr int kComparedPoses = 16;
#endif
    const int touching = CompareOracles(s, Request(s, 0.4, 1.5, 0), options, kComparedPoses, 11);
    EXPECT_GE(touching, kComparedPoses / 2) << "the poses should exercise contacts";
  }
}

TEST(RegionOfInterest, SameAnswersWithTheWideCoarseField) {
  // The planner's coarse stage: 0.8 mm voxels, field dilated to 3.2 mm.
  OracleOptions options;
  options.voxel_size_mm = 0.8;
  options.sdf_dilation_voxels = 4;
  const Scene& s = Synthetic(true);
  CompareOracles(s, Request(s, 0.4, 1.5, 0), options, 12, 12);
}

TEST(RegionOfInterest, DropsTheBaseAndKeepsEveryTooth) {
  const Scene& s = Synthetic(true);
  OracleOptions fine;
  fine.voxel_size_mm = 0.2;
  const RegionOfInterestRequest request = Request(s, 0.5, 2.0, OracleReadRadiusMm(fine, 0.3));
  const RegionOfInterest roi = ComputeRegionOfInterest(s.lower, s.upper, request);
  const double lower_share =
      static_cast<double>(roi.stats.lower_kept) / static_cast<double>(roi.stats.lower_total);
  const double upper_share =
      static_cast<double>(roi.stats.upper_kept) / static_cast<double>(roi.stats.upper_total);
  std::cout << "[ roi      ] kept " << lower_share << " of the open lower's triangles, "
            << upper_share << " of the upper's\n";
  EXPECT_LT(lower_share,
            0.95);  // the lower's walls are long triangles, kept whole when they reach up
  EXPECT_LT(upper_share, 0.8);
  // The upper's flat back (facing +y, 13 mm above the occlusal plane) is all dropped.
  std::size_t back = 0;
  for (const std::uint32_t t : roi.upper.original_triangle)
    back += s.upper->face_normals[t].y() > 0.99 ? 1 : 0;
  EXPECT_EQ(back, 0u);
  // The closed lower is one closed component: kept whole (a cut would lose its interior).
  const Scene& closed = Synthetic(false);
  const RegionOfInterest whole_lower = ComputeRegionOfInterest(closed.lower, closed.upper, request);
  EXPECT_EQ(whole_lower.lower.mesh, closed.lower);
  EXPECT_EQ(whole_lower.stats.upper_kept, roi.stats.upper_kept);
  // Every tooth keeps triangles; the maps point at whole-mesh triangles of the same part.
  for (const RegionMesh* m : {&roi.lower, &roi.upper}) {
    const io::TriangleMesh& whole = m == &roi.lower ? *s.lower : *s.upper;
    ASSERT_EQ(m->mesh->parts.size(), whole.parts.size());
    ASSERT_EQ(m->original_triangle.size(), m->mesh->num_triangles());
    EXPECT_EQ(m->mesh->ConsistencyError(), "");
    std::set<std::int32_t> parts;
    for (std::size_t t = 0; t < m->mesh->num_triangles(); ++t) {
      const std::uint32_t o = m->original_triangle[t];
      ASSERT_LT(o, whole.num_triangles());
      EXPECT_EQ(m->mesh->triangle_part[t], whole.triangle_part[o]);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(m->mesh->corner(t, k), whole.corner(o, k));
      parts.insert(m->mesh->triangle_part[t]);
    }
    for (std::size_t p = 1; p < whole.parts.size(); ++p)
      EXPECT_TRUE(parts.count(static_cast<std::int32_t>(p))) << p;
  }
}

TEST(RegionOfInterest, DisplacementBoundHoldsAndReachGrowsWithTheBounds) {
  const Scene& s = Synthetic();
  std::mt19937 rng(5);
  double last_reach = 0.0;
  std::vector<std::uint32_t> last_lower, last_upper;
  for (const double scale : {0.0, 0.25, 0.5, 1.0, 2.0}) {
    const RegionOfInterestRequest r = Request(s, 3.0 * scale, 5.0 * scale, 2.0);
    const RegionOfInterest roi = ComputeRegionOfInterest(s.lower, s.upper, r);
    EXPECT_GE(roi.stats.reach_mm, last_reach);
    EXPECT_DOUBLE_EQ(roi.stats.reach_mm, roi.stats.band_mm + roi.stats.displacement_mm);
    // Nested: a larger reach keeps every triangle a smaller one kept.
    EXPECT_TRUE(std::includes(roi.lower.original_triangle.begin(),
                              roi.lower.original_triangle.end(), last_lower.begin(),
                              last_lower.end()));
    EXPECT_TRUE(std::includes(roi.upper.original_triangle.begin(),
                              roi.upper.original_triangle.end(), last_upper.begin(),
                              last_upper.end()));
    // Sound: no vertex moves farther than D at poses within the bounds (corners included).
    for (int i = 0; i < 50; ++i) {
      EXPECT_TRUE(
          RegionCoversPose(*s.upper, r.X_LU_start, PoseWithin(r, &rng), roi.stats.displacement_mm));
    }
    last_reach = roi.stats.reach_mm;
    last_lower = roi.lower.original_triangle;
    last_upper = roi.upper.original_triangle;
  }
  // Locking every rotation leaves the translation norm: sqrt(3) * 3 mm.
  RegionOfInterestRequest r = Request(s, 3.0, 5.0, 0.0);
  r.locked = {false, false, false, true, true, true};
  EXPECT_NEAR(MaxDisplacementMm(*s.upper, r), std::sqrt(27.0), test::kExactMm);
}

// One selector serves every band of a schedule with the answer of a selection made for that
// band alone: the same kept triangles, sub-meshes and stats.
TEST(RegionOfInterest, SelectorGivesEachBandsOwnSelection) {
  const Scene& s = Synthetic(/*open_lower=*/true);
  const RegionOfInterestRequest base = Request(s, 1.0, 2.0, 0.0);
  const RegionSelector selector(s.lower, s.upper, base);
  EXPECT_GE(selector.seconds(), 0.0);
  std::size_t cut = 0;
  for (const double band : {0.5, 2.0, 1.0, 4.0}) {  // out of order on purpose
    RegionOfInterestRequest r = base;
    r.band_mm = band;
    const RegionOfInterest alone = ComputeRegionOfInterest(s.lower, s.upper, r);
    const RegionOfInterest shared = selector.Select(band);
    EXPECT_EQ(shared.lower.original_triangle, alone.lower.original_triangle) << band;
    EXPECT_EQ(shared.upper.original_triangle, alone.upper.original_triangle) << band;
    EXPECT_EQ(shared.lower.mesh->vertices, alone.lower.mesh->vertices) << band;
    EXPECT_EQ(shared.upper.mesh->triangles, alone.upper.mesh->triangles) << band;
    EXPECT_EQ(shared.stats.reach_mm, alone.stats.reach_mm);
    EXPECT_EQ(shared.stats.lower_kept, alone.stats.lower_kept);
    EXPECT_EQ(shared.stats.upper_kept, alone.stats.upper_kept);
    cut += alone.stats.lower_total - alone.stats.lower_kept;
  }
  EXPECT_GT(cut, 0u);  // the bands cut something: the comparison is not of whole meshes only
  EXPECT_THROW(selector.Select(-1.0), std::invalid_argument);
}

// A selection made again from its kept lists (a saved one, read back) is the selection: the same
// sub-meshes vertex for vertex (whole meshes shared when nothing is cut) and stats; lists that
// are not increasing indices of the meshes are refused.
TEST(RegionOfInterest, RegionOfKeptIsTheSelection) {
  const Scene& s = Synthetic(/*open_lower=*/true);
  const RegionSelector selector(s.lower, s.upper, Request(s, 1.0, 2.0, 0.0));
  for (const double band : {0.5, 1.0, 1000.0}) {
    const RegionOfInterest made = selector.Select(band);
    const RegionOfInterest again = RegionOfKept(s.lower, s.upper, made.lower.original_triangle,
                                                made.upper.original_triangle, made.stats);
    for (const auto& [a, b] : {std::pair{&made.lower, &again.lower}, {&made.upper, &again.upper}}) {
      EXPECT_EQ(b->original_triangle, a->original_triangle) << band;
      EXPECT_EQ(b->mesh->vertices, a->mesh->vertices) << band;
      EXPECT_EQ(b->mesh->triangles, a->mesh->triangles) << band;
      EXPECT_EQ(b->mesh->triangle_part, a->mesh->triangle_part) << band;
      EXPECT_EQ(b->mesh->face_normals.size(), a->mesh->face_normals.size()) << band;
      EXPECT_EQ(b->mesh == s.lower || b->mesh == s.upper, a->mesh == s.lower || a->mesh == s.upper)
          << band;
    }
    EXPECT_EQ(again.stats.reach_mm, made.stats.reach_mm);
    EXPECT_EQ(again.stats.lower_kept, made.stats.lower_kept);
    EXPECT_EQ(again.stats.upper_total, made.stats.upper_total);
  }
  EXPECT_LT(selector.Select(0.5).stats.lower_kept, s.lower->num_triangles());  // a real cut
  const RegionOfInterestStats stats;
  EXPECT_THROW(RegionOfKept(s.lower, s.upper, {2, 1}, {}, stats), std::invalid_argument);
  EXPECT_THROW(RegionOfKept(s.lower, s.upper, {1, 1}, {}, stats), std::invalid_argument);
  EXPECT_THROW(RegionOfKept(s.lower, s.upper, {},
                            {static_cast<std::uint32_t>(s.upper->num_triangles())}, stats),
               std::invalid_argument);
  EXPECT_THROW(RegionOfKept(nullptr, s.upper, {}, {}, stats), std::invalid_argument);
}

TEST(RegionOfInterest, HugeBoundsKeepEverything) {
  const Scene& s = Synthetic();
  const RegionOfInterest roi =
      ComputeRegionOfInterest(s.lower, s.upper, Request(s, 100.0, 180.0, 3.0));
  EXPECT_EQ(roi.stats.lower_kept, roi.stats.lower_total);
  EXPECT_EQ(roi.stats.upper_kept, roi.stats.upper_total);
  EXPECT_EQ(roi.lower.mesh, s.lower);  // nothing cut: the whole mesh is shared
  EXPECT_EQ(roi.upper.mesh, s.upper);
}

TEST(RegionOfInterest, CutBordersAreFartherThanTheReachFromTheOtherJaw) {
  const Scene& s = Synthetic(true);
  const RegionOfInterestRequest r = Request(s, 0.5, 2.0, 1.0);
  const RegionOfInterest roi = ComputeRegionOfInterest(s.lower, s.upper, r);
  const io::TriangleMesh upper_L = s.upper->Transformed(r.X_LU_start);
  const PseudoNormals upper_normals(upper_L);
  // Border vertices of the cut lower not on the border of the whole (open) lower: the cuts,
  // checked by brute force against the upper at the start pose.
  const PseudoNormals lower_normals(*roi.lower.mesh), whole_normals(*s.lower);
  std::set<std::uint32_t> border;
  for (std::uint32_t t = 0; t < roi.lower.mesh->num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      Vector3d bary = Vector3d::Zero();
      bary[k] = 1.0;  // corner k
      if (lower_normals.OnBoundary(t, bary) &&
          !whole_normals.OnBoundary(roi.lower.original_triangle[t], bary)) {
        border.insert(static_cast<std::uint32_t>(roi.lower.mesh->triangles[t][k]));
      }
    }
  }
  ASSERT_FALSE(border.empty());
  int checked = 0;
  for (const std::uint32_t v : border) {
    if (checked++ % 7 != 0) continue;  // a deterministic seventh of them: brute force is O(T)
    SignedDistanceSample d;
    ASSERT_TRUE(SignedDistanceBruteForce(upper_L, upper_normals, roi.lower.mesh->vertices[v], &d));
    EXPECT_GT(std::abs(d.distance), roi.stats.reach_mm) << "border vertex " << v;
  }
}

TEST(RegionOfInterest, RejectsBadRequests) {
  const Scene& s = Synthetic();
  RegionOfInterestRequest r = Request(s, 1.0, 1.0, 1.0);
  r.band_mm = -1.0;
  EXPECT_THROW(ComputeRegionOfInterest(s.lower, s.upper, r), std::invalid_argument);
  r = Request(s, 1.0, 1.0, 1.0);
  r.bound_min[4] = 2.0;
  EXPECT_THROW(ComputeRegionOfInterest(s.lower, s.upper, r), std::invalid_argument);
  EXPECT_THROW(ComputeRegionOfInterest(nullptr, s.upper, Request(s, 1.0, 1.0, 1.0)),
               std::invalid_argument);
}

}  // namespace
}  // namespace occlude::collision
