// The ground truth of `occlude bench --accuracy`: the exact signed distance
// agrees with brute force over all triangles (closed and open meshes, inside
// and outside, within and beyond the search radius), and the fixed upper
// samples lie on their triangles, cover them to the spacing and hold every
// vertex once.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <set>

#include "bench/bench_accuracy_score_internal.h"
#include "bench/bench_accuracy_truth_internal.h"
#include "bench_files.h"
#include "occlude/collision/signed_distance.h"
#include "test_common.h"

namespace occlude::test {
namespace {

// A closed sphere and, as an open mesh, the same sphere without its top cap.
io::TriangleMesh OpenSphere() {
  const io::TriangleMesh closed = MakeSphere(Eigen::Vector3d(1, 2, 3), 4.0, 12, 16);
  io::TriangleMesh open = closed;
  open.triangles.clear();
  for (std::size_t t = 0; t < closed.num_triangles(); ++t) {
    const Eigen::Vector3d c =
        (closed.corner(t, 0) + closed.corner(t, 1) + closed.corner(t, 2)) / 3.0;
    if (c.z() < 3.0 + 3.0) open.triangles.push_back(closed.triangles[t]);
  }
  open.triangle_part.assign(open.triangles.size(), 0);
  open.ComputeFaceNormals();
  return open;
}

void ExpectMatchesBruteForce(const io::TriangleMesh& mesh, double cell_mm) {
  auto shared = std::make_shared<io::TriangleMesh>(mesh);
  const app::LowerDistance truth(shared, cell_mm);
  const collision::PseudoNormals normals(mesh);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-7.0, 9.0), radius(0.05, 3.0);
  int found = 0, inside = 0;
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng) + 1.0);
    const double max_mm = radius(rng);
    collision::SignedDistanceSample ref;
    ASSERT_TRUE(collision::SignedDistanceBruteForce(mesh, normals, p, &ref));
    double d = 0.0;
    const bool ok = truth.Signed(p, max_mm, &d);
    EXPECT_EQ(ok, std::abs(ref.distance) <= max_mm) << p.transpose() << " max " << max_mm;
    if (ok) {
      EXPECT_NEAR(d, ref.distance, kExactMm) << p.transpose();
      ++found;
      if (d < 0) ++inside;
    }
    if (std::abs(ref.distance) <= max_mm) {
      EXPECT_TRUE(truth.MayBeWithin(p, max_mm));
    }
  }
  EXPECT_GT(found, 40);  // the test saw points within the radius...
  EXPECT_GT(inside, 5);  // ...and inside the surface
}

TEST(AccuracyTruthTest, SignedDistanceMatchesBruteForceOnAClosedMesh) {
  ExpectMatchesBruteForce(MakeSphere(Eigen::Vector3d(1, 2, 3), 4.0, 12, 16), 0.0);
  ExpectMatchesBruteForce(MakeSphere(Eigen::Vector3d(1, 2, 3), 4.0, 12, 16), 0.3);
}

TEST(AccuracyTruthTest, SignedDistanceMatchesBruteForceOnAnOpenMesh) {
  ExpectMatchesBruteForce(OpenSphere(), 0.0);
}

TEST(AccuracyTruthTest, SamplesLieOnTheirTrianglesCoverThemAndHoldEveryVertexOnce) {
  const io::TriangleMesh sphere = MakeSphere(Eigen::Vector3d::Zero(), 3.0, 8, 10);
  const double spacing = 0.25;
  const app::UpperSamples samples(std::make_shared<io::TriangleMesh>(sphere), spacing);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::set<std::array<double, 3>> vertices_seen;
  std::size_t total = 0;
  std::vector<Eigen::Vector3d> p;
  for (std::size_t t = 0; t < sphere.num_triangles(); ++t) {
    samples.Generate(t, &p);
    ASSERT_EQ(p.size(), samples.end(t) - samples.begin(t));
    total += p.size();
    const Eigen::Vector3d a = sphere.corner(t, 0), b = sphere.corner(t, 1), c = sphere.corner(t, 2);
    const Eigen::Vector3d n = (b - a).cross(c - a);
    for (const Eigen::Vector3d& q : p) {
      // On the triangle's plane and inside it (barycentric weights >= 0).
      EXPECT_NEAR((q - a).dot(n.normalized()), 0.0, kExactMm);
      const double w_a = (b - q).cross(c - q).dot(n) / n.squaredNorm();
      const double w_b = (c - q).cross(a - q).dot(n) / n.squaredNorm();
      EXPECT_GE(w_a, -kExactMm);
      EXPECT_GE(w_b, -kExactMm);
      EXPECT_GE(1.0 - w_a - w_b, -kExactMm);
      for (int k = 0; k < 3; ++k) {
        if ((q - sphere.corner(t, k)).norm() < kExactMm) {
          EXPECT_TRUE(vertices_seen.insert({q.x(), q.y(), q.z()}).second) << "vertex sampled twice";
        }
      }
    }
    for (std::size_t id = samples.begin(t); id < samples.end(t); ++id) {
      EXPECT_EQ(samples.TriangleOf(static_cast<std::uint32_t>(id)), t);
    }
    // Every point of the triangle is within the spacing of one of its samples.
    for (int i = 0; i < 20; ++i) {
      double x = u(rng), y = u(rng);
      if (x + y > 1) x = 1 - x, y = 1 - y;
      const Eigen::Vector3d q = a + x * (b - a) + y * (c - a);
      double nearest = 1e9;
      for (const Eigen::Vector3d& s : p) nearest = std::min(nearest, (s - q).norm());
      EXPECT_LE(nearest, spacing);
    }
  }
  EXPECT_EQ(vertices_seen.size(), sphere.num_vertices());
  EXPECT_EQ(total, samples.size());
}

// Analytic truth: the sphere pushed 0.15 mm into the box's top face (z = 0).
// Near the pole every sample's signed distance to the box is its height z, the
// deepest sample is the pole vertex (depth 0.15 mm), and the truth contacts are
// exactly the samples below the band.
TEST(AccuracyTruthTest, SphereIntoABoxHasTheAnalyticDepthAndDistances) {
  const auto lower = std::make_shared<io::TriangleMesh>(SphereOnBoxLower());
  const auto upper = std::make_shared<io::TriangleMesh>(SphereOnBoxUpper());
  const app::LowerDistance truth(lower);
  const app::UpperSamples samples(upper, 0.1);
  const double depth = 0.15, delta = 0.1;
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
  X_LU.translation().z() = -depth;
  app::PoseTruth pose(truth, samples, X_LU, delta);
  EXPECT_NEAR(pose.max_penetration_mm(), depth, kExactMm);
  ASSERT_GT(pose.contact_ids().size(), 10u);
  // contact_d is stored as float: 1e-6 mm covers its rounding at these sizes.
  constexpr double kFloatMm = 1e-6;
  for (std::size_t i = 0; i < pose.contact_ids().size(); ++i) {
    const Eigen::Vector3d p_L = X_LU * pose.contact_p_U()[i];
    EXPECT_NEAR(pose.contact_d()[i], p_L.z(), kFloatMm);
    EXPECT_LE(p_L.z(), delta + kFloatMm);
  }
  std::size_t expected = 0;
  std::vector<Eigen::Vector3d> p;
  for (std::size_t t = 0; t < samples.num_triangles(); ++t) {
    samples.Generate(t, &p);
    for (const Eigen::Vector3d& q : p) expected += (X_LU * q).z() <= delta;
  }
  EXPECT_EQ(pose.contact_ids().size(), expected);
}

}  // namespace
}  // namespace occlude::test
