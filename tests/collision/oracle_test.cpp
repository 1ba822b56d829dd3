// The contact and penetration oracle on analytic scenes: a block resting on a
// slab (contact area, penetration depth and area, minimum distance), agreement
// between accuracy levels, residual gradients against finite differences, and
// robustness (far apart, nested, no NaN).
#include "occlude/collision/oracle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>

#include "test_common.h"

namespace occlude::collision {
namespace {

using io::TriangleMesh;

// Lower: a slab whose top face is y = 0. Upper: a 4 x 4 mm block whose bottom
// face is y = 0 in U. With X_LU = translation (0, g, 0) the gap is g.
class OracleBlockTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto lower = std::make_shared<TriangleMesh>(test::MakeBox({-3, -2, -3}, {3, 0, 3}));
    auto upper = std::make_shared<TriangleMesh>(test::MakeBox({-2, 0, -2}, {2, 4, 2}));
    OracleOptions options;
    options.voxel_size_mm = 0.2;
    options.sample_spacing_mm = 0.25;
    oracle_ = std::make_unique<JawOracle>(lower, upper, options);
  }
  static void TearDownTestSuite() { oracle_.reset(); }
  static Eigen::Isometry3d Gap(double g) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation().y() = g;
    return X;
  }
  static std::unique_ptr<JawOracle> oracle_;
};
std::unique_ptr<JawOracle> OracleBlockTest::oracle_;

constexpr double kBottomArea = 16.0;  // mm^2
// Side-face samples within the band add at most band * perimeter.
constexpr double kSideStrip = 0.1 * 16.0;

TEST_F(OracleBlockTest, ContactAreaIsTheBottomFaceWithinTheBand) {
  for (AccuracyLevel level : {AccuracyLevel::kSubVoxel, AccuracyLevel::kExact}) {
    OracleRequest req;
    req.level = level;
    OracleResult res;
    oracle_->Query(Gap(0.05), req, &res);
    EXPECT_EQ(res.level, level);
    EXPECT_GE(res.contact_area_mm2, kBottomArea - 1e-6) << ToString(level);
    EXPECT_LE(res.contact_area_mm2, kBottomArea + kSideStrip) << ToString(level);
    EXPECT_EQ(res.max_penetration_mm, 0.0) << ToString(level);
    EXPECT_NEAR(res.min_distance_mm, 0.05, level == AccuracyLevel::kExact ? 1e-9 : 0.01);
    EXPECT_NEAR(res.left_share + res.right_share, 1.0, 1e-12);
    EXPECT_NEAR(res.anterior_share + res.posterior_share, 1.0, 1e-12);
  }
}

// LowerInterior against the grid's own classes (brute force): points at random around the slab,
// on and an ulp off its voxels' faces, and far beyond its box on every side.
TEST_F(OracleBlockTest, LowerInteriorIsTheGridsInteriorClass) {
  const VoxelGrid& grid = oracle_->lower_tree().grid();
  ASSERT_FALSE(grid.interior_runs.empty());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  std::uniform_int_distribution<int> face(-3, 40);
  std::size_t interior = 0;
  for (int i = 0; i < 30000; ++i) {
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    if (i % 3 == 1) {  // on a voxel face, or an ulp off it, along one axis
      const int a = i % 9 / 3;
      const double f = grid.origin_F[a] + grid.voxel_size_mm * face(rng);
      p[a] = i % 2 == 0 ? f : std::nextafter(f, i % 4 == 1 ? 1e9 : -1e9);
    }
    if (i % 50 == 0) p *= 1e3;  // far away
    const bool expected = grid.IsInterior(grid.VoxelOf(p));
    interior += expected ? 1 : 0;
    EXPECT_EQ(oracle_->LowerInterior(p), expected) << p.transpose();
  }
  EXPECT_GT(interior, 1000u);
}

TEST_F(OracleBlockTest, PenetrationDepthAndArea) {
  OracleRequest req;
  req.level = AccuracyLevel::kExact;
  OracleResult res;
  oracle_->Query(Gap(-0.08), req, &res);
  EXPECT_NEAR(res.max_penetration_mm, 0.08, 1e-9);
  EXPECT_GE(res.penetration_area_mm2, kBottomArea - 1e-6);
  // Side samples stand for pieces up to one spacing tall: the strip is quantized.
  EXPECT_LE(res.penetration_area_mm2, kBottomArea + (0.08 + 0.25) * 16.0);
  EXPECT_NEAR(res.deepest_p_L.y(), -0.08, 1e-9);
  req.level = AccuracyLevel::kSubVoxel;
  oracle_->Query(Gap(-0.08), req, &res);
  EXPECT_NEAR(res.max_penetration_mm, 0.08, 0.01);
}

TEST_F(OracleBlockTest, FarApartHasNothingAndTouchesNothing) {
  OracleRequest req;
  OracleResult res;
  oracle_->Query(Gap(3.0), req, &res);
  EXPECT_EQ(res.contact_area_mm2, 0.0);
  EXPECT_EQ(res.max_penetration_mm, 0.0);
  EXPECT_EQ(res.samples_evaluated, 0u);  // the broad phase found no cell
  EXPECT_TRUE(std::isinf(res.min_distance_mm));
}

TEST_F(OracleBlockTest, VoxelLevelIsWithinAVoxel) {
  OracleRequest req;
  req.level = AccuracyLevel::kVoxel;
  OracleResult res;
  oracle_->Query(Gap(0.05), req, &res);
  // One sample per voxel, lower distance at voxel centres: within a voxel diagonal.
  EXPECT_NEAR(res.min_distance_mm, 0.05, 0.2 * std::sqrt(3.0));
  EXPECT_GT(res.samples_evaluated, 0u);
}

TEST_F(OracleBlockTest, ResidualGradientsMatchFiniteDifferences) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1, 1);
  OracleRequest req;
  req.level = AccuracyLevel::kExact;
  req.residuals = true;
  req.keep_points = false;
  req.pivot_L = Eigen::Vector3d(0.5, 2.0, -0.3);
  Eigen::Isometry3d X = Gap(0.2);
  X.linear() = Eigen::AngleAxisd(0.02, Eigen::Vector3d(1, 0, 1).normalized()).toRotationMatrix();
  OracleResult res;
  oracle_->Query(X, req, &res);
  ASSERT_GT(res.residuals.size(), 20u);
  const double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    // Apply the k-th unit update (t in mm, w in rad about the pivot) to each residual's point.
    Eigen::Matrix<double, 6, 1> step = Eigen::Matrix<double, 6, 1>::Zero();
    step[k] = h;
    const Eigen::Matrix3d Rw =
        Eigen::AngleAxisd(step.tail<3>().norm(), step.tail<3>().norm() > 0
                                                     ? step.tail<3>().normalized()
                                                     : Eigen::Vector3d::UnitX())
            .toRotationMatrix();
    for (std::size_t i = 0; i < res.residuals.size(); i += 7) {
      const DistanceResidual& r = res.residuals[i];
      const Eigen::Vector3d moved = req.pivot_L + Rw * (r.p_L - req.pivot_L) + step.head<3>();
      // The lower's top face is y = 0 near the block: d = y exactly there.
      if (std::abs(r.p_L.x()) > 1.9 || std::abs(r.p_L.z()) > 1.9 || r.p_L.y() > 0.5) continue;
      const double fd = (moved.y() - r.p_L.y()) / h;
      EXPECT_NEAR(r.gradient[k], fd, 1e-5) << "component " << k;
    }
  }
}

TEST(OracleRobustnessTest, NestedFarAndRotatedPosesNeverGiveNaN) {
  auto lower = std::make_shared<TriangleMesh>(test::MakeSphere({0, 0, 0}, 3.0, 12, 16));
  auto upper = std::make_shared<TriangleMesh>(test::MakeSphere({0, 0, 0}, 1.0, 8, 12));
  OracleOptions options;
  options.voxel_size_mm = 0.25;
  const JawOracle oracle(lower, upper, options);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 40; ++i) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() =
        Eigen::AngleAxisd(3.1 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized())
            .toRotationMatrix();
    X.translation() = (i % 4 == 0 ? 0.0 : 6.0) * Eigen::Vector3d(u(rng), u(rng), u(rng));
    for (AccuracyLevel level :
         {AccuracyLevel::kVoxel, AccuracyLevel::kSubVoxel, AccuracyLevel::kExact}) {
      OracleRequest req;
      req.level = level;
      req.residuals = true;
      OracleResult res;
      oracle.Query(X, req, &res);
      ASSERT_TRUE(std::isfinite(res.contact_area_mm2));
      ASSERT_TRUE(std::isfinite(res.max_penetration_mm));
      ASSERT_TRUE(std::isfinite(res.penetration_area_mm2));
      for (const auto& r : res.residuals) ASSERT_TRUE(r.gradient.allFinite());
    }
  }
}

TEST(OracleValidationTest, RejectsBadRequests) {
  auto box = std::make_shared<TriangleMesh>(test::MakeBox({0, 0, 0}, {1, 1, 1}));
  const JawOracle oracle(box, box, OracleOptions{});
  OracleResult res;
  OracleRequest req;
  req.contact_band_mm = -0.1;
  EXPECT_THROW(oracle.Query(Eigen::Isometry3d::Identity(), req, &res), std::invalid_argument);
  req.contact_band_mm = std::nan("");
  EXPECT_THROW(oracle.Query(Eigen::Isometry3d::Identity(), req, &res), std::invalid_argument);
}

TEST(OracleValidationTest, RejectsBadFieldBoundOptions) {
  auto box = std::make_shared<TriangleMesh>(test::MakeBox({0, 0, 0}, {1, 1, 1}));
  OracleOptions options;
  options.field_bound_mm = std::nan("");
  EXPECT_THROW(JawOracle(box, box, options), std::invalid_argument);
  options.field_bound_mm = 0.1;
  options.field_bound_depth_mm = -0.1;
  EXPECT_THROW(JawOracle(box, box, options), std::invalid_argument);
  options.field_bound_depth_mm = std::numeric_limits<double>::infinity();
  EXPECT_THROW(JawOracle(box, box, options), std::invalid_argument);
  options.field_bound_mm = -1.0;  // no field bound: valid
  options.field_bound_depth_mm = 0.3;
  EXPECT_NO_THROW(JawOracle(box, box, options));
}

// A 4 x 4 mm sheet (facing -y, at y = 0.01 in U) triangulated 20 times finer
// than the sample spacing, over the slab of OracleBlockTest's lower jaw.
TriangleMesh FineSheet(int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i)
      m.vertices.emplace_back(-2.0 + 4.0 * i / n, 0.01, -2.0 + 4.0 * j / n);
  }
  const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(i + (n + 1) * j); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {  // counter-clockwise seen from below (-y)
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  m.parts.push_back({"sheet", 0});
  m.triangle_part.assign(m.triangles.size(), 0);
  m.ComputeFaceNormals();
  return m;
}

TEST(OracleSamplesTest, FineTrianglesAreMergedToTheSpacingKeepingAreaAndSurface) {
  constexpr int kCells = 200;  // 0.02 mm grid: 80,000 triangles of 0.0002 mm^2
  auto lower = std::make_shared<TriangleMesh>(test::MakeBox({-3, -2, -3}, {3, 0, 3}));
  auto upper = std::make_shared<TriangleMesh>(FineSheet(kCells));
  OracleOptions options;
  options.voxel_size_mm = 0.2;
  options.sample_spacing_mm = 0.1;  // k = 2: sub-cells of 0.1 mm
  const JawOracle oracle(lower, upper, options);
  // One sample per occupied 0.1 mm sub-cell: 40 x 40 of them over the flat sheet
  // (it crosses no sub-cell boundary in y), against 80,000 triangle centroids.
  EXPECT_LE(oracle.num_samples(), 1600u);
  EXPECT_GE(oracle.num_samples(), 1600u);
  // The samples as the peers of `occlude bench` read them: points of the sheet in U, and
  // areas adding up to the sheet's.
  ASSERT_EQ(oracle.samples_U().size(), oracle.num_samples());
  ASSERT_EQ(oracle.sample_areas_mm2().size(), oracle.num_samples());
  double area = 0.0;
  for (std::size_t i = 0; i < oracle.num_samples(); ++i) {
    EXPECT_NEAR(oracle.samples_U()[i].y(), 0.01f, 1e-6f);
    EXPECT_LE(oracle.samples_U()[i].head<3>().cwiseAbs().maxCoeff(), 2.0f + 1e-6f);
    area += static_cast<double>(oracle.sample_areas_mm2()[i]);
  }
  EXPECT_NEAR(area, 16.0, 1e-3);
  for (AccuracyLevel level : {AccuracyLevel::kSubVoxel, AccuracyLevel::kExact}) {
    OracleRequest req;
    req.level = level;
    OracleResult res;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation().y() = 0.04;  // gap 0.05 mm: the whole sheet within the band
    oracle.Query(X, req, &res);
    EXPECT_NEAR(res.contact_area_mm2, 16.0, 1e-4)
        << ToString(level);  // every triangle's area, once
    EXPECT_EQ(res.contact_samples, oracle.num_samples()) << ToString(level);
    // Merged samples are points of the sheet (members, not centroids between them).
    EXPECT_NEAR(res.min_distance_mm, 0.05, level == AccuracyLevel::kExact ? 1e-6 : 0.01)
        << ToString(level);
    X.translation().y() = -0.04;  // 0.03 mm into the slab
    oracle.Query(X, req, &res);
    EXPECT_NEAR(res.max_penetration_mm, 0.03, level == AccuracyLevel::kExact ? 1e-6 : 0.01)
        << ToString(level);
    EXPECT_NEAR(res.penetration_area_mm2, 16.0, 1e-4) << ToString(level);
  }
}

}  // namespace
}  // namespace occlude::collision

#include "occlude/io/synthetic_jaws.h"

namespace occlude::collision {
namespace {

TEST(OracleSyntheticTest, GroundTruthBiteTouchesOnBothSidesWithoutPenetration) {
  io::SyntheticJawOptions o;
  o.triangles_per_jaw = 5000;
  const io::SyntheticJawPair jaws = io::MakeSyntheticJawPair(o);
  OracleOptions options;
  options.voxel_size_mm = 0.5;  // coarse enough to keep the sanitizer lane fast
  const auto lower = std::make_shared<io::TriangleMesh>(jaws.lower_L);
  const auto upper = std::make_shared<io::TriangleMesh>(jaws.upper_U);
  options.arch = EstimateArchFrame(jaws.lower_L, jaws.upper_U.Transformed(jaws.X_LU));
  const JawOracle oracle(lower, upper, options);
  OracleRequest req;
  req.level = AccuracyLevel::kExact;
  OracleResult res;
  oracle.Query(jaws.X_LU, req, &res);
  EXPECT_LE(res.max_penetration_mm, 0.011);  // the generator's contract, 0.01 mm
  EXPECT_GT(res.contact_area_mm2, 1.0);
  EXPECT_GT(res.left_share, 0.2);
  EXPECT_GT(res.right_share, 0.2);
  EXPECT_GT(res.posterior_share, 0.5);
  // Pushed 0.2 mm into the bite it interpenetrates by at least 0.15 mm.
  oracle.Query(Eigen::Translation3d(-0.2 * jaws.occlusal_axis_L) * jaws.X_LU, req, &res);
  EXPECT_GE(res.max_penetration_mm, 0.15);
  // Opened 0.5 mm: nothing within the 0.1 mm band.
  oracle.Query(Eigen::Translation3d(0.5 * jaws.occlusal_axis_L) * jaws.X_LU, req, &res);
  EXPECT_EQ(res.contact_area_mm2, 0.0);
  EXPECT_EQ(res.max_penetration_mm, 0.0);
}

}  // namespace
}  // namespace occlude::collision
