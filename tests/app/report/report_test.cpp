// The report on the synthetic pair (5,000 triangles per jaw), checked by content:
// at the ground-truth bite the contact colours lie on the known contact points
// (projected into both occlusal maps) and the penetration colour appears nowhere;
// pushed 0.2 mm into the lower jaw the penetration colour appears on both maps;
// report.html embeds the pictures and tables; pose.json reads back. (The command:
// tests/app/cli/cmd_report_test.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>

#include "config/case_config.h"
#include "config/pose_file.h"
#include "occlude/collision/closest_point.h"
#include "occlude/io/synthetic_jaws.h"
#include "report/report_analysis.h"
#include "report/report_document.h"
#include "report/report_images.h"
#include "test_common.h"

namespace occlude::test {
namespace {

using app::Arch;
namespace render = app::render;

// Fraction of truth contacts that must show a contact colour within kWindowPx:
// a few contacts of the design sit on a steep wall, where the occlusal view
// sees them edge-on.
constexpr double kMinContactHitRate = 0.9;
constexpr int kWindowPx = 3;
// Pushed 0.2 mm into the lower jaw, penetration covers whole cusp tips: at least this many pixels.
constexpr int kMinPenetrationPixels = 200;

const std::string kSyntheticConfig =
    "[synthetic]\ntriangles = 5000\nseed = 1\n[report]\nimage_width_px = 900\n";

struct Fixture {
  app::CaseConfig config;
  std::unique_ptr<app::CaseSession> session;
  app::JawPair jaws;
  app::ReportAnalysis truth, pushed;
};

const Fixture& Shared() {
  static const Fixture* f = [] {
    auto* x = new Fixture;
    x->config = app::ParseCaseConfig(kSyntheticConfig, "synthetic.toml");
    x->session = std::make_unique<app::CaseSession>(x->config);
    x->jaws = x->session->jaws();
    x->truth = app::AnalyzePose(*x->session, Eigen::Isometry3d::Identity());
    const Eigen::Isometry3d down(Eigen::Translation3d(0, -0.2, 0));
    x->pushed = app::AnalyzePose(*x->session, down);
    return x;
  }();
  return *f;
}

render::MapScale Scale(const app::CaseConfig& c) {
  return {c.report.map_max_mm, c.contact_band_mm, c.report.map_penetration_from_mm};
}

int CountInMap(const app::MapImage& m, bool (*pred)(render::Rgb)) {
  int n = 0;
  for (int y = m.map_y; y < m.map_y + m.map_height; ++y) {
    for (int x = m.map_x; x < m.map_x + m.map_width; ++x) n += pred(m.image.At(x, y)) ? 1 : 0;
  }
  return n;
}

bool ContactNear(const app::MapImage& m, const Eigen::Vector3d& p_L) {
  const Eigen::Vector2d px = m.view.ToPixel(p_L);
  for (int dy = -kWindowPx; dy <= kWindowPx; ++dy) {
    for (int dx = -kWindowPx; dx <= kWindowPx; ++dx) {
      const int x = static_cast<int>(px.x()) + dx, y = static_cast<int>(px.y()) + dy;
      if (x < m.map_x || y < m.map_y || x >= m.map_x + m.map_width || y >= m.map_y + m.map_height)
        continue;
      if (render::IsContactColour(m.image.At(x, y))) return true;
    }
  }
  return false;
}

TEST(ReportColours, ScaleConventions) {
  const render::MapScale s;
  EXPECT_TRUE(render::IsContactColour(render::DistanceColour(0.0, s)));
  EXPECT_TRUE(render::IsContactColour(render::DistanceColour(0.1, s)));
  EXPECT_FALSE(render::IsContactColour(render::DistanceColour(0.3, s)));
  EXPECT_TRUE(render::IsPenetrationColour(render::DistanceColour(-0.05, s)));
  EXPECT_FALSE(render::IsPenetrationColour(
      render::DistanceColour(-0.005, s)));  // within the display tolerance
  for (double d = -0.005; d <= 1.0; d += 0.01)
    EXPECT_FALSE(render::IsPenetrationColour(render::DistanceColour(d, s))) << d;
  EXPECT_EQ(render::DistanceColour(0.6, s), render::kFarColour);
}

TEST(ReportAnalysisTest, TruthPoseHasContactsOnBothSidesAndNoPenetration) {
  const auto& a = Shared().truth;
  EXPECT_LT(a.oracle.max_penetration_mm, io::kSyntheticContactToleranceMm);
  EXPECT_GT(a.oracle.contact_area_mm2, 0.5);
  EXPECT_GE(a.spots.size(), 8u);
  EXPECT_GT(a.oracle.left_share, 0.2);
  EXPECT_GT(a.oracle.right_share, 0.2);
  EXPECT_EQ(a.teeth.size(), 28u);  // 14 teeth per arch
  int upper_teeth_in_contact = 0;
  for (const auto& t : a.teeth) upper_teeth_in_contact += t.upper && t.contact_area_mm2 > 0 ? 1 : 0;
  EXPECT_GE(upper_teeth_in_contact, 6);
  EXPECT_EQ(a.lower_vertex_mm.size(), Shared().jaws.lower_L->num_vertices());
}

// The maps' vertex distances against brute force (every triangle of the other jaw): a vertex
// within the reach holds its distance (up to sign), one beyond holds the far value. The cells
// that cull far vertices must never drop a near one, on either jaw, at either pose.
TEST(ReportAnalysisTest, VertexDistancesMatchBruteForceWithinTheReach) {
  const Fixture& f = Shared();
  for (const app::ReportAnalysis* a : {&f.truth, &f.pushed}) {
    const auto check = [&](const io::TriangleMesh& mesh, const Eigen::Isometry3d& X_FM,
                           const io::TriangleMesh& field, const std::vector<float>& got) {
      ASSERT_EQ(got.size(), mesh.num_vertices());
      int near = 0, far = 0;
      for (std::size_t i = 0; i < mesh.num_vertices(); i += 2) {
        const Eigen::Vector3d p = X_FM * mesh.vertices[i];
        double best2 = std::numeric_limits<double>::infinity();
        for (std::size_t t = 0; t < field.num_triangles(); ++t) {
          best2 = std::min(best2, collision::ClosestPointOnTriangle(
                                      p, field.corner(t, 0), field.corner(t, 1), field.corner(t, 2))
                                      .squared_distance);
        }
        const double d = std::sqrt(best2);
        if (d < a->reach_mm - 1e-6) {
          EXPECT_NEAR(std::abs(got[i]), d, 1e-5) << "vertex " << i;
          ++near;
        } else if (d > a->reach_mm + 1e-6) {
          EXPECT_EQ(got[i], render::kFarValue) << "vertex " << i << " at " << d << " mm";
          ++far;
        }
      }
      EXPECT_GT(near, 20);
      EXPECT_GT(far, 20);
    };
    check(*f.jaws.upper_U, a->X_LU, *f.jaws.lower_L, a->upper_vertex_mm);
    check(*f.jaws.lower_L, a->X_LU.inverse(), *f.jaws.upper_U, a->lower_vertex_mm);
  }
}

// The poses analysed together (two at a time) answer as each analysed alone, in their order.
TEST(ReportAnalysisTest, AnalyzePosesMatchesAnalyzePoseAtEachPose) {
  const Fixture& f = Shared();
  const Eigen::Isometry3d turned(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()) *
                                 Eigen::Translation3d(0.1, 0.15, 0.0));
  const std::vector<Eigen::Isometry3d> poses = {turned, Eigen::Isometry3d::Identity(),
                                                f.pushed.X_LU};
  const std::vector<app::ReportAnalysis> together = app::AnalyzePoses(*f.session, poses);
  ASSERT_EQ(together.size(), poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    SCOPED_TRACE(i);
    const app::ReportAnalysis alone = app::AnalyzePose(*f.session, poses[i]);
    const app::ReportAnalysis& a = together[i];
    EXPECT_TRUE(a.X_LU.isApprox(poses[i], 0.0));
    EXPECT_EQ(a.oracle.contact_area_mm2, alone.oracle.contact_area_mm2);
    EXPECT_EQ(a.oracle.max_penetration_mm, alone.oracle.max_penetration_mm);
    EXPECT_EQ(a.upper_vertex_mm, alone.upper_vertex_mm);
    EXPECT_EQ(a.lower_vertex_mm, alone.lower_vertex_mm);
    EXPECT_EQ(a.spots.size(), alone.spots.size());
    EXPECT_EQ(a.teeth.size(), alone.teeth.size());
    EXPECT_EQ(a.relationships.overjet.mm, alone.relationships.overjet.mm);
    EXPECT_EQ(a.relationships.midline_deviation.mm, alone.relationships.midline_deviation.mm);
  }
  EXPECT_GT(together[1].oracle.contact_area_mm2, 0.5);  // the truth pose is among them
  EXPECT_TRUE(app::AnalyzePoses(*f.session, {}).empty());
}

TEST(ReportImages, TruthContactsShowTheContactColourAndNoPenetration) {
  const Fixture& f = Shared();
  ASSERT_FALSE(f.jaws.truth_contacts_L.empty());
  for (const Arch arch : {Arch::kLower, Arch::kUpper}) {
    const app::MapImage m = app::RenderContactMap(arch, f.jaws, f.truth, Scale(f.config), 900);
    SCOPED_TRACE(arch == Arch::kLower ? "lower map" : "upper map");
    int hits = 0;
    for (const auto& p : f.jaws.truth_contacts_L) hits += ContactNear(m, p) ? 1 : 0;
    EXPECT_GE(hits, kMinContactHitRate * static_cast<double>(f.jaws.truth_contacts_L.size()))
        << hits << " of " << f.jaws.truth_contacts_L.size();
    EXPECT_EQ(CountInMap(m, render::IsPenetrationColour), 0);
    EXPECT_GT(CountInMap(m, render::IsContactColour), 50);
  }
}

TEST(ReportImages, PushedIntoTheLowerJawShowsPenetration) {
  const Fixture& f = Shared();
  EXPECT_GT(f.pushed.oracle.max_penetration_mm, 0.15);
  for (const Arch arch : {Arch::kLower, Arch::kUpper}) {
    const app::MapImage m = app::RenderContactMap(arch, f.jaws, f.pushed, Scale(f.config), 900);
    EXPECT_GT(CountInMap(m, render::IsPenetrationColour), kMinPenetrationPixels);
  }
}

TEST(ReportDocumentTest, Base64) {
  EXPECT_EQ(app::Base64(""), "");
  EXPECT_EQ(app::Base64("M"), "TQ==");
  EXPECT_EQ(app::Base64("Ma"), "TWE=");
  EXPECT_EQ(app::Base64("Man"), "TWFu");
}

TEST(ReportDocumentTest, HtmlEmbedsPicturesAndTablesAndPoseReadsBack) {
  const Fixture& f = Shared();
  app::ReportInputs in;
  in.config = &f.config;
  in.jaws = &f.jaws;
  in.analysis = &f.pushed;
  in.pose_source = "test";
  const std::string png = app::EncodePng(
      app::RenderSideView(app::SideView::kFrontal, f.jaws, f.pushed, Scale(f.config), 400));
  EXPECT_EQ(png.substr(1, 3), "PNG");
  in.pictures = {{"Frontal view", png, "frontal.png"}};
  const std::string html = app::ReportHtml(in);
  EXPECT_NE(html.find("src=\"data:image/png;base64," + app::Base64(png).substr(0, 40)),
            std::string::npos);
  for (const char* s : {"<h2>Pose of the upper jaw</h2>", "<h2>Contact</h2>", "<h2>Per tooth</h2>",
                        "<h2>Settings</h2>", "maximum penetration", "EXCEEDS", "<td>14</td>"}) {
    EXPECT_NE(html.find(s), std::string::npos) << s;
  }
  EXPECT_NE(app::MetricsJson(in).find("\"within_allowed\": false"), std::string::npos);
  TempDir tmp;
  std::ofstream(tmp / "pose.json") << app::PoseJson(in);
  EXPECT_TRUE(app::ReadPoseFile(tmp / "pose.json").isApprox(f.pushed.X_LU, 1e-12));
}

}  // namespace
}  // namespace occlude::test
