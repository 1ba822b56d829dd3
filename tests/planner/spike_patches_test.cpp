// Spike patches (evaluation.h): penetrating samples grouped by proximity, and
// the patches steeper than a hemisphere flagged as scanner artefacts, on
// analytic shapes: a spherical cap pressed into a plane (real contact, never a
// spike however large the cap), a needle (a spike), the size cap, chains.
#include <gtest/gtest.h>

#include <cmath>

#include "occlude/angles.h"
#include "occlude/planner/evaluation.h"

namespace occlude::planner {
namespace {

using V = Eigen::Vector3d;

// Samples of the part of a sphere of radius r (centre above the plane z = 0 by r - h)
// below the plane: a cap of depth h, on a grid of `spacing` in xy, each with its area.
std::vector<PenetratingSample> Cap(double r, double h, double spacing, const V& at) {
  std::vector<PenetratingSample> out;
  const double a = std::sqrt(2.0 * r * h - h * h);  // cap radius in the plane
  for (double x = -a; x <= a; x += spacing) {
    for (double y = -a; y <= a; y += spacing) {
      const double rho2 = x * x + y * y;
      if (rho2 > a * a) continue;
      const double z = (r - h) - std::sqrt(r * r - rho2);  // sphere surface below the plane
      const double slope = r / std::sqrt(r * r - rho2);    // area of the surface over dA
      out.push_back({at + V(x, y, z), -z, spacing * spacing * slope});
    }
  }
  return out;
}

TEST(SpikePatches, SphericalCapIsNotASpike) {
  // A crown of radius 2 mm pressed 0.3 mm and 1.5 mm deep: depth below the cap's disc radius.
  for (const double h : {0.05, 0.3, 1.5}) {
    const auto cap = Cap(2.0, h, 0.1, V::Zero());
    const auto patches = PenetrationPatches(cap, 0.25, 100.0);
    ASSERT_EQ(patches.size(), 1u) << h;
    EXPECT_NEAR(patches[0].area_mm2, 2.0 * kPi * 2.0 * h, 0.15 * 2.0 * kPi * 2.0 * h) << h;
    EXPECT_NEAR(patches[0].depth_mm, h, 0.02) << h;
    EXPECT_FALSE(patches[0].spike) << h;
  }
}

TEST(SpikePatches, NeedleIsASpikeAndOnlyItsSamples) {
  std::vector<PenetratingSample> s = Cap(2.0, 0.2, 0.1, V::Zero());
  const std::size_t cap_size = s.size();
  // A needle 10 mm away: five samples along 1.2 mm of depth, 0.02 mm^2 each.
  for (int i = 0; i < 5; ++i) s.push_back({V(10.0, 0.0, -0.3 * i), 0.3 * i + 0.1, 0.02});
  const auto patches = PenetrationPatches(s, 0.35, 5.0);
  ASSERT_EQ(patches.size(), 2u);
  EXPECT_FALSE(patches[0].spike);
  EXPECT_TRUE(patches[1].spike);
  EXPECT_NEAR(patches[1].depth_mm, 1.3, 1e-12);
  EXPECT_EQ(patches[1].deepest_L, V(10.0, 0.0, -1.2));
  const std::vector<bool> member = SpikeMembers(s, 0.35, 5.0);
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(member[i], i >= cap_size) << i;
}

TEST(SpikePatches, SizeCapAndOffSwitch) {
  // A steep patch (1.5 mm deep over 2 mm^2) is a spike under a 5 mm^2 cap, not under 1 mm^2.
  std::vector<PenetratingSample> s;
  for (int i = 0; i < 20; ++i) s.push_back({V(0.1 * i, 0.0, 0.0), 1.5, 0.1});
  EXPECT_TRUE(PenetrationPatches(s, 0.25, 5.0)[0].spike);
  EXPECT_FALSE(PenetrationPatches(s, 0.25, 1.0)[0].spike);
  const std::vector<bool> off = SpikeMembers(s, 0.25, 0.0);
  for (const bool b : off) EXPECT_FALSE(b);
}

TEST(SpikePatches, ChainsLinkAndGapsSeparate) {
  // Samples 0.2 mm apart chain into one patch; a 0.5 mm gap splits it (link 0.25 mm).
  std::vector<PenetratingSample> s;
  for (int i = 0; i < 10; ++i) s.push_back({V(0.2 * i, 0.0, 0.0), 0.01, 0.04});
  for (int i = 0; i < 10; ++i) s.push_back({V(2.3 + 0.2 * i, 0.0, 0.0), 0.01, 0.04});
  const auto patches = PenetrationPatches(s, 0.25, 5.0);
  ASSERT_EQ(patches.size(), 2u);
  EXPECT_EQ(patches[0].members.size(), 10u);
  EXPECT_EQ(patches[1].members.size(), 10u);
  EXPECT_TRUE(PenetrationPatches({}, 0.25, 5.0).empty());
}

}  // namespace
}  // namespace occlude::planner
