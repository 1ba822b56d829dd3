// Numerical robustness of the contact oracle, on the synthetic jaw
// pair and on nested spheres, with seeded random poses: every number of every
// result is finite (or +inf where documented), at all three accuracy levels,
// for poses far apart (up to 10^12 mm), nested jaws (partly nested ones show
// penetration; wholly nested ones are a known gap, see below), rotations down to
// 1e-12 rad (which change nothing measurable) and up to whole turns and 10^6 rad
// (a whole turn gives back the pose's own answer); a non-finite or non-rigid
// pose is refused, never answered with NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "occlude/angles.h"
#include "occlude/collision/oracle.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::collision {
namespace {

constexpr AccuracyLevel kLevels[] = {AccuracyLevel::kVoxel, AccuracyLevel::kSubVoxel,
                                     AccuracyLevel::kExact};
// Random poses per test (fewer in the sanitizer lane, where every query is ~30x slower).
#ifdef OCCLUDE_SANITIZED
constexpr int kPoses = 4;
#else
constexpr int kPoses = 12;
#endif

// Every figure of a result is a real number: no NaN anywhere, no infinity but
// min_distance_mm's +inf for "nothing evaluated".
void ExpectFinite(const OracleResult& r, const std::string& where) {
  SCOPED_TRACE(where);
  for (const double v : {r.max_penetration_mm, r.penetration_area_mm2, r.contact_area_mm2,
                         r.left_share, r.right_share, r.anterior_share, r.posterior_share}) {
    ASSERT_TRUE(std::isfinite(v)) << v;
    ASSERT_GE(v, 0.0);
  }
  ASSERT_FALSE(std::isnan(r.min_distance_mm));
  ASSERT_TRUE(std::isfinite(r.min_distance_mm) || r.min_distance_mm > 0) << r.min_distance_mm;
  ASSERT_TRUE(r.deepest_p_L.allFinite());
  for (const double share : {r.left_share + r.right_share, r.anterior_share + r.posterior_share}) {
    // Shares of the contact area: they add up to 1 when there is contact, else 0.
    ASSERT_NEAR(share, r.contact_area_mm2 > 0 ? 1.0 : 0.0, 1e-9);
  }
  for (const auto* points : {&r.contacts, &r.penetrations}) {
    for (const SurfacePoint& p : *points) {
      ASSERT_TRUE(p.p_L.allFinite());
      ASSERT_TRUE(std::isfinite(p.distance_mm));
      ASSERT_TRUE(std::isfinite(p.area_mm2));
    }
  }
  for (const PartTotals& t : r.parts) {
    ASSERT_TRUE(std::isfinite(t.contact_area_mm2) && std::isfinite(t.penetration_area_mm2) &&
                std::isfinite(t.max_penetration_mm));
  }
  for (const DistanceResidual& d : r.residuals) {
    ASSERT_TRUE(std::isfinite(d.distance_mm));
    ASSERT_TRUE(d.gradient.allFinite());
    ASSERT_TRUE(d.p_L.allFinite());
  }
}

// The synthetic bite touches at cusp tips, which the test fixture's sparse samples
// (1 mm) miss at the default 0.1 mm band: the rotation tests count contact within this.
constexpr double kWideBandMm = 0.5;

OracleResult Query(const JawOracle& oracle, const Eigen::Isometry3d& X_LU, AccuracyLevel level,
                   const Eigen::Vector3d& pivot_L = Eigen::Vector3d::Zero(), double band_mm = 0.1) {
  OracleRequest request;
  request.level = level;
  request.contact_band_mm = band_mm;
  request.residuals = true;
  request.pivot_L = pivot_L;
  OracleResult result;
  oracle.Query(X_LU, request, &result);
  return result;
}

Eigen::Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Vector3d v(n(rng), n(rng), n(rng));
  return v.norm() > 1e-9 ? Eigen::Vector3d(v.normalized()) : Eigen::Vector3d::UnitX();
}

Eigen::Isometry3d Rotation(double angle_rad, const Eigen::Vector3d& axis,
                           const Eigen::Vector3d& pivot) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(angle_rad, axis).toRotationMatrix();
  X.translation() = pivot - X.linear() * pivot;
  return X;
}

// The synthetic pair at its ground-truth bite (U moved into L, so X_LU = identity
// is the bite), at a coarse voxel and sample spacing so that the sanitizer lane
// (a Debug build, each test its own process) stays quick: the synthetic jaws'
// long triangles give 1.4 million samples at the default 0.3 mm spacing.
struct Bite {
  std::unique_ptr<JawOracle> oracle;
  Eigen::Vector3d centre_L;  ///< of the upper jaw, the pivot of the rotations
};

const Bite& SyntheticBite() {
  static const Bite* bite = [] {
    io::SyntheticJawOptions options;
    options.triangles_per_jaw = 5000;
    const io::SyntheticJawPair pair = io::MakeSyntheticJawPair(options);
    auto lower = std::make_shared<io::TriangleMesh>(pair.lower_L);
    auto upper = std::make_shared<io::TriangleMesh>(pair.upper_U.Transformed(pair.X_LU));
    OracleOptions oracle_options;
    oracle_options.voxel_size_mm = 0.8;
    oracle_options.sample_spacing_mm = 1.0;
    auto* b = new Bite;
    b->oracle = std::make_unique<JawOracle>(lower, upper, oracle_options);
    b->centre_L = upper->Bounds().center();
    return b;
  }();
  return *bite;
}

TEST(OracleRobustness, FarApartPosesTouchNothing) {
  const JawOracle& oracle = *SyntheticBite().oracle;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> exponent(3.0, 12.0);  // 1 m .. 10^6 km away
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int i = 0; i < kPoses; ++i) {
    Eigen::Isometry3d X = Rotation(angle(rng), RandomUnit(rng), Eigen::Vector3d::Zero());
    X.translation() += std::pow(10.0, exponent(rng)) * RandomUnit(rng);
    for (const AccuracyLevel level : kLevels) {
      const OracleResult r = Query(oracle, X, level);
      ExpectFinite(r, "far pose " + std::to_string(i));
      EXPECT_EQ(r.contact_area_mm2, 0.0);
      EXPECT_EQ(r.max_penetration_mm, 0.0);
      EXPECT_EQ(r.deep_samples, 0u);
      EXPECT_TRUE(r.contacts.empty() && r.penetrations.empty());
    }
  }
}

TEST(OracleRobustness, RandomPosesNearTheBiteStayFinite) {
  const Bite& bite = SyntheticBite();
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> shift(-1.5, 1.5), angle(-0.2, 0.2);
  for (int i = 0; i < kPoses; ++i) {
    Eigen::Isometry3d X = Rotation(angle(rng), RandomUnit(rng), bite.centre_L);
    X.translation() += Eigen::Vector3d(shift(rng), shift(rng), shift(rng));
    for (const AccuracyLevel level : kLevels) {
      ExpectFinite(Query(*bite.oracle, X, level, bite.centre_L), "near pose " + std::to_string(i));
    }
  }
}

// Rotations of 1e-12 .. 1e-6 rad about the upper's centre move no sample by more
// than 1e-4 mm (the jaw is < 100 mm across): the answers at the bite barely move.
// The oracle keeps sample offsets and sphere centres in floats: a pose other than
// the identity rounds each coordinate (< 100 mm) by up to 2^-24 of it, a few 1e-6 mm.
constexpr double kFloatRoundingMm = 1e-5;

TEST(OracleRobustness, TinyRotationsChangeNothingMeasurable) {
  const Bite& bite = SyntheticBite();
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> exponent(-12.0, -6.0);
  constexpr double kSpanMm = 100.0;
  for (const AccuracyLevel level : {AccuracyLevel::kSubVoxel, AccuracyLevel::kExact}) {
    const OracleResult at_bite =
        Query(*bite.oracle, Eigen::Isometry3d::Identity(), level, bite.centre_L, kWideBandMm);
    ASSERT_GT(at_bite.contact_area_mm2, 0.0);
    for (int i = 0; i < kPoses; ++i) {
      const double angle = std::pow(10.0, exponent(rng));
      const OracleResult r = Query(*bite.oracle, Rotation(angle, RandomUnit(rng), bite.centre_L),
                                   level, bite.centre_L, kWideBandMm);
      ExpectFinite(r, "tiny rotation " + std::to_string(angle));
      // The exact distance is 1-Lipschitz in the sample position, the trilinear one
      // sqrt(3)-Lipschitz (each partial derivative is a corner difference over s).
      const double moved = std::sqrt(3.0) * angle * kSpanMm;
      EXPECT_NEAR(r.min_distance_mm, at_bite.min_distance_mm, moved + kFloatRoundingMm) << angle;
      EXPECT_NEAR(r.max_penetration_mm, at_bite.max_penetration_mm, moved + kFloatRoundingMm)
          << angle;
    }
  }
}

// Whole turns (2 pi k, up to k = 10^5) give back the answer at the bite, to the
// rounding of the rotation matrix and of the floats; huge and near-half-turn angles stay finite.
TEST(OracleRobustness, HugeRotationsStayFiniteAndWholeTurnsComeBack) {
  const Bite& bite = SyntheticBite();
  const OracleResult at_bite = Query(*bite.oracle, Eigen::Isometry3d::Identity(),
                                     AccuracyLevel::kSubVoxel, bite.centre_L, kWideBandMm);
  ASSERT_GT(at_bite.contact_area_mm2, 0.0);
  std::mt19937 rng(14);
  for (const double turns : {1.0, 3.0, 1e3, 1e5}) {
    const double angle = 2.0 * kPi * turns;
    const OracleResult r = Query(*bite.oracle, Rotation(angle, RandomUnit(rng), bite.centre_L),
                                 AccuracyLevel::kSubVoxel, bite.centre_L, kWideBandMm);
    ExpectFinite(r, "whole turns " + std::to_string(turns));
    // 2 pi k in double is off by up to its ulp (~1e-16 relative), which moves samples
    // 100 mm from the pivot by that angle times 100 mm (times sqrt(3), as above).
    const double tolerance = 1e-15 * angle * 100.0 * std::sqrt(3.0) + kFloatRoundingMm;
    EXPECT_NEAR(r.min_distance_mm, at_bite.min_distance_mm, tolerance) << turns;
    EXPECT_NEAR(r.contact_area_mm2, at_bite.contact_area_mm2, 0.01 * at_bite.contact_area_mm2)
        << turns;
  }
  for (const double angle : {kPi, kPi - 1e-9, -kPi, 1e6, -1e6, 123456.789}) {
    for (const AccuracyLevel level : kLevels) {
      ExpectFinite(Query(*bite.oracle, Rotation(angle, RandomUnit(rng), bite.centre_L), level,
                         bite.centre_L),
                   "angle " + std::to_string(angle));
    }
  }
}

// A small sphere (r 3 mm) in a large one (r 10 mm), at voxel 0.5 mm.
struct Nested {
  std::shared_ptr<io::TriangleMesh> large, small;
  std::unique_ptr<JawOracle> small_in_large;  ///< lower = large, upper = small
};

const Nested& NestedSpheres() {
  static const Nested* nested = [] {
    auto* n = new Nested;
    n->large = std::make_shared<io::TriangleMesh>(test::MakeSphere({0, 0, 0}, 10.0, 24, 32));
    n->small = std::make_shared<io::TriangleMesh>(test::MakeSphere({0, 0, 0}, 3.0, 12, 16));
    OracleOptions options;
    options.voxel_size_mm = 0.5;
    n->small_in_large = std::make_unique<JawOracle>(n->large, n->small, options);
    return n;
  }();
  return *nested;
}

// Random poses keeping the small sphere wholly inside (offset + 3 < 10).
std::vector<Eigen::Isometry3d> InsidePoses(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> angle(-kPi, kPi), offset(0.0, 5.0);
  std::vector<Eigen::Isometry3d> poses;
  for (int i = 0; i < count; ++i) {
    Eigen::Isometry3d X = Rotation(angle(rng), RandomUnit(rng), Eigen::Vector3d::Zero());
    X.translation() = offset(rng) * RandomUnit(rng);
    poses.push_back(X);
  }
  return poses;
}

TEST(OracleRobustness, FullyNestedJawsStayFinite) {
  const Nested& n = NestedSpheres();
  int i = 0;
  for (const Eigen::Isometry3d& X : InsidePoses(kPoses, 15)) {
    for (const AccuracyLevel level : kLevels) {
      const OracleResult r = Query(*n.small_in_large, X, level);
      ExpectFinite(r, "nested pose " + std::to_string(i));
      EXPECT_EQ(r.contact_area_mm2, 0.0) << "nested pose " << i;  // 2 mm or more from the surface
    }
    ++i;
  }
  // The other way round (the lower inside the upper) the upper's samples are all
  // outside the lower: the one-sided oracle sees a gap, but a finite one.
  OracleOptions options;
  options.voxel_size_mm = 0.5;
  const JawOracle inside_out(n.small, n.large, options);
  for (const AccuracyLevel level : kLevels) {
    const OracleResult r = Query(inside_out, Eigen::Isometry3d::Identity(), level);
    ExpectFinite(r, "lower inside upper");
    EXPECT_EQ(r.max_penetration_mm, 0.0);
  }
}

// Straddling the large sphere's surface (centre 9 mm out), the small one
// penetrates it: the oracle measures that at every level and orientation.
TEST(OracleRobustness, PartlyNestedJawsReportPenetration) {
  const Nested& n = NestedSpheres();
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  for (int i = 0; i < kPoses; ++i) {
    Eigen::Isometry3d X = Rotation(angle(rng), RandomUnit(rng), Eigen::Vector3d::Zero());
    X.translation() = 9.0 * RandomUnit(rng);
    for (const AccuracyLevel level : kLevels) {
      const OracleResult r = Query(*n.small_in_large, X, level);
      ExpectFinite(r, "straddling pose " + std::to_string(i));
      EXPECT_GT(r.penetration_area_mm2, 0.0)
          << "straddling pose " << i << " at " << ToString(level);
      EXPECT_GT(r.max_penetration_mm, 0.0);
    }
  }
}

// An upper jaw wholly inside a closed lower, farther than the oracle's reach from its
// surface (no upper cell is found), still counts as interpenetrating: its samples are
// classified against the lower's Interior voxels (JawOracle::CountNestedPieces), so a
// planner never takes it for a free pose like jaws far apart.
TEST(OracleRobustness, FullyNestedJawsAreReportedAsInterpenetrating) {
  const Nested& n = NestedSpheres();
  int i = 0;
  for (const Eigen::Isometry3d& X : InsidePoses(kPoses, 15)) {
    for (const AccuracyLevel level : kLevels) {
      const OracleResult r = Query(*n.small_in_large, X, level);
      EXPECT_TRUE(r.deep_samples > 0 || r.penetration_area_mm2 > 0)
          << "nested pose " << i << " at " << ToString(level);
    }
    ++i;
  }
}

// An upper in two pieces, one inside the closed lower and one outside it, none within reach
// of its surface: exactly the samples of the piece inside count as deep (one interior test
// per connected piece, JawOracle::CountNestedPieces), whichever piece it is.
TEST(OracleRobustness, OnlyTheNestedPieceOfAnUpperCountsAsDeep) {
  const Nested& n = NestedSpheres();
  auto two = std::make_shared<io::TriangleMesh>(test::MakeSphere({0, 0, 0}, 3.0, 12, 16));
  two->Append(test::MakeSphere({20, 0, 0}, 3.0, 12, 16));
  OracleOptions options;
  options.voxel_size_mm = 0.5;
  const JawOracle oracle(n.large, two, options);
  Eigen::Isometry3d shifted = Eigen::Isometry3d::Identity();
  shifted.translation() = Eigen::Vector3d(-20, 0, 0);
  Eigen::Isometry3d apart = Eigen::Isometry3d::Identity();
  apart.translation() = Eigen::Vector3d(0, 30, 0);
  for (const AccuracyLevel level : kLevels) {
    const OracleResult first = Query(oracle, Eigen::Isometry3d::Identity(), level);
    const OracleResult second = Query(oracle, shifted, level);
    const OracleResult none = Query(oracle, apart, level);
    EXPECT_EQ(first.cells, 0u) << ToString(level);
    EXPECT_GT(first.deep_samples, 0u) << ToString(level);
    EXPECT_GT(second.deep_samples, 0u) << ToString(level);
    EXPECT_EQ(first.deep_samples + second.deep_samples, oracle.num_samples()) << ToString(level);
    EXPECT_EQ(none.deep_samples, 0u) << ToString(level);
  }
}

TEST(OracleRobustness, NonFiniteOrNonRigidPosesAreRefused) {
  const JawOracle& oracle = *SyntheticBite().oracle;
  OracleResult r;
  const OracleRequest request;
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation().x() = bad;
    EXPECT_THROW(oracle.Query(X, request, &r), std::invalid_argument) << bad;
    X = Eigen::Isometry3d::Identity();
    X.linear()(1, 2) = bad;
    EXPECT_THROW(oracle.Query(X, request, &r), std::invalid_argument) << bad;
  }
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() *= 2.0;
  EXPECT_THROW(oracle.Query(scaled, request, &r), std::invalid_argument);
}

}  // namespace
}  // namespace occlude::collision
