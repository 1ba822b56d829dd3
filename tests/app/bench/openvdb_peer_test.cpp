// Tests of the OpenVDB peer adapter (app/bench/openvdb_peer.h) on a box with known distances:
// the level set's values and band, and the counts of Sample() (contact, penetration, deep,
// outside) as the oracle counts them. Every test but the first skips when occlude was built
// without OpenVDB.
#include "bench/openvdb_peer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "test_common.h"

namespace occlude::app {
namespace {

#define OCCLUDE_REQUIRE_OPENVDB() \
  if (!OpenVdbPeer::Available()) GTEST_SKIP() << OpenVdbPeer::Unavailable()

constexpr double kVoxelMm = 0.25;
constexpr int kHalfWidth = 3;  // band +-0.75 mm

// The lower jaw stand-in: the box [0,10]^3 in L (closed, so OpenVDB's flood fill signs it).
io::TriangleMesh Box() {
  return test::MakeBox(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(10.0));
}

// Upper samples: an n x n grid on the plane z = 0 of U over x, y in [3, 7], 0.01 mm^2 each.
std::vector<Eigen::Vector3f> Sheet(int n) {
  std::vector<Eigen::Vector3f> p;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      p.emplace_back(3.0f + 4.0f * static_cast<float>(i) / static_cast<float>(n - 1),
                     3.0f + 4.0f * static_cast<float>(j) / static_cast<float>(n - 1), 0.0f);
    }
  }
  return p;
}

// The pose putting U's plane z = 0 at height z in L.
Eigen::Isometry3d AtHeight(double z) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation().z() = z;
  return X;
}

// A build with the library has the peers' module beside its binaries: a missing or stale
// module fails here instead of skipping every other test.
TEST(OpenVdbPeerTest, AvailableInEveryBuildWithTheLibrary) {
  if (!OCCLUDE_BUILT_WITH_OPENVDB) GTEST_SKIP() << OpenVdbPeer::Unavailable();
  EXPECT_TRUE(OpenVdbPeer::Available()) << OpenVdbPeer::Unavailable();
  EXPECT_EQ(OpenVdbPeer::Unavailable(), "");
}

TEST(OpenVdbPeerTest, StubOrRealMatchesAvailability) {
  if (OpenVdbPeer::Available()) {
    EXPECT_NO_THROW(OpenVdbPeer(Box(), kVoxelMm, kHalfWidth));
  } else {
    EXPECT_THROW(OpenVdbPeer(Box(), kVoxelMm, kHalfWidth), std::runtime_error);
  }
}

TEST(OpenVdbPeerTest, BadArgumentsThrow) {
  OCCLUDE_REQUIRE_OPENVDB();
  EXPECT_THROW(OpenVdbPeer(Box(), 0.0, kHalfWidth), std::invalid_argument);
  EXPECT_THROW(OpenVdbPeer(Box(), kVoxelMm, 0), std::invalid_argument);
  EXPECT_THROW(OpenVdbPeer(io::TriangleMesh{}, kVoxelMm, kHalfWidth), std::invalid_argument);
  const OpenVdbPeer peer(Box(), kVoxelMm, kHalfWidth);
  EXPECT_THROW(peer.Sample(Sheet(3), {1.0f}, AtHeight(10.0), {}), std::invalid_argument);
}

TEST(OpenVdbPeerTest, BoxLevelSetHasTheBoxDistancesWithinTheBand) {
  OCCLUDE_REQUIRE_OPENVDB();
  const OpenVdbPeer peer(Box(), kVoxelMm, kHalfWidth);
  EXPECT_EQ(peer.voxel_mm(), kVoxelMm);
  EXPECT_EQ(peer.half_width_voxels(), kHalfWidth);
  EXPECT_GE(peer.build_seconds(), 0.0);
  EXPECT_GT(peer.active_voxels(), 6u * 40u * 40u);  // both sides of six 10 x 10 mm faces
  EXPECT_GT(peer.approx_bytes(), peer.active_voxels() * sizeof(float));
  // Over the middle of the top face the distance is linear in z, so the trilinear value is
  // the exact one up to the float grid (1e-5 mm here): positive outside, negative inside.
  for (const double z : {10.6, 10.3, 10.05, 10.0, 9.9, 9.5}) {
    EXPECT_NEAR(peer.Value({5.1, 4.9, z}), z - 10.0, 1e-4) << z;
  }
  // Beyond the band: the background value, +-0.75 mm on the side of the point.
  EXPECT_FLOAT_EQ(static_cast<float>(peer.Value({5, 5, 12})), 0.75f);
  EXPECT_FLOAT_EQ(static_cast<float>(peer.Value({5, 5, 5})), -0.75f);
}

TEST(OpenVdbPeerTest, SamplesCountAsTheOracleCounts) {
  OCCLUDE_REQUIRE_OPENVDB();
  const OpenVdbPeer peer(Box(), kVoxelMm, kHalfWidth);
  const std::vector<Eigen::Vector3f> sheet = Sheet(20);
  const std::vector<float> area(sheet.size(), 0.01f);
  OpenVdbCountRule rule;
  rule.contact_band_mm = 0.1;
  rule.penetration_depth_mm = 0.5;
  // 0.05 mm above the top face: every sample a contact.
  OpenVdbSampleResult r = peer.Sample(sheet, area, AtHeight(10.05), rule);
  EXPECT_EQ(r.samples_evaluated, 400u);
  EXPECT_EQ(r.contact_samples, 400u);
  EXPECT_NEAR(r.contact_area_mm2, 4.0, 1e-4);
  EXPECT_EQ(r.penetration_samples, 0u);
  EXPECT_NEAR(r.min_distance_mm, 0.05, 1e-4);
  // 0.3 mm above: beyond the contact band, within the grid's: nothing counts, the minimum known.
  r = peer.Sample(sheet, area, AtHeight(10.3), rule);
  EXPECT_EQ(r.contact_samples + r.penetration_samples + r.deep_samples, 0u);
  EXPECT_NEAR(r.min_distance_mm, 0.3, 1e-4);
  // 0.2 mm in: every sample penetrates, 0.2 mm deep.
  r = peer.Sample(sheet, area, AtHeight(9.8), rule);
  EXPECT_EQ(r.penetration_samples, 400u);
  EXPECT_NEAR(r.penetration_area_mm2, 4.0, 1e-4);
  EXPECT_NEAR(r.max_penetration_mm, 0.2, 1e-4);
  EXPECT_EQ(r.contact_samples, 0u);
  // 0.6 mm in: within the grid's band but deeper than the rule's: neither counted nor deep.
  r = peer.Sample(sheet, area, AtHeight(9.4), rule);
  EXPECT_EQ(r.contact_samples + r.penetration_samples + r.deep_samples, 0u);
  // 5 mm in: beyond the band, inside: every sample deep. 2 mm out: nothing at all.
  r = peer.Sample(sheet, area, AtHeight(5.0), rule);
  EXPECT_EQ(r.deep_samples, 400u);
  EXPECT_EQ(r.contact_samples + r.penetration_samples, 0u);
  r = peer.Sample(sheet, area, AtHeight(12.0), rule);
  EXPECT_EQ(r.contact_samples + r.penetration_samples + r.deep_samples, 0u);
  EXPECT_TRUE(std::isinf(r.min_distance_mm));
}

TEST(OpenVdbPeerTest, ThePoseRotatesAndMovesTheSamples) {
  OCCLUDE_REQUIRE_OPENVDB();
  const OpenVdbPeer peer(Box(), kVoxelMm, kHalfWidth);
  // The sheet turned a quarter about y and moved to x = 10.05: 0.05 mm off the face x = 10.
  std::vector<Eigen::Vector3f> sheet = Sheet(10);
  for (Eigen::Vector3f& p : sheet) p = Eigen::Vector3f(p.x() - 5.0f, p.y(), 0.0f);  // x in +-2
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.rotate(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));  // U's x -> L's -z
  X.pretranslate(Eigen::Vector3d(10.05, 0.0, 5.0));
  const OpenVdbSampleResult r =
      peer.Sample(sheet, std::vector<float>(sheet.size(), 1.0f), X, OpenVdbCountRule{});
  EXPECT_EQ(r.contact_samples, sheet.size());
  EXPECT_NEAR(r.min_distance_mm, 0.05, 1e-4);
}

}  // namespace
}  // namespace occlude::app
