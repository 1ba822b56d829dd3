// The viewer page in a real browser (headless Chromium, WebGL on SwiftShader): the
// canvas is drawn, no script error, switching proposals, views and the upper jaw's
// mode change the picture, a click on a surface reads the distance and the tooth
// there, and the page requests nothing from the network. One browser for the suite;
// every test skips, saying why, where no browser can run.
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "headless_browser.h"
#include "occlude/collision/closest_point.h"
#include "occlude/io/dental.h"
#include "test_common.h"
#include "viewer/viewer_data_internal.h"
#include "viewer_fixture.h"

namespace occlude::app {
namespace {

using nlohmann::json;

class ViewerBrowserTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    fixture_ = test::MakeSyntheticViewer(3).release();
    folder_ = new test::TempDir();
    page_ = (folder_->path() / "viewer.html").string();
    std::ofstream(page_, std::ios::binary) << ViewerPage(fixture_->inputs);
    browser_ = test::HeadlessBrowser::Launch(&why_).release();
  }
  static void TearDownTestSuite() {
    delete browser_;
    delete folder_;
    delete fixture_;
  }
  void SetUp() override {
    if (browser_ == nullptr) GTEST_SKIP() << "no headless browser: " << why_;
    browser_->Navigate("file://" + page_);
    ASSERT_TRUE(browser_->WaitFor("document.body.dataset.viewerReady === '1'", 60))
        << "the viewer did not draw; errors: " << json(browser_->Errors()).dump();
  }
  json Js(const std::string& expression) { return browser_->Evaluate(expression); }

  static test::ViewerFixture* fixture_;
  static test::TempDir* folder_;
  static std::string page_;
  static test::HeadlessBrowser* browser_;
  static std::string why_;
};
test::ViewerFixture* ViewerBrowserTest::fixture_ = nullptr;
test::TempDir* ViewerBrowserTest::folder_ = nullptr;
std::string ViewerBrowserTest::page_;
test::HeadlessBrowser* ViewerBrowserTest::browser_ = nullptr;
std::string ViewerBrowserTest::why_;

/// A drawn canvas covers at least this share of its pixels with the jaws.
constexpr double kMinDrawnShare = 0.05;
/// A change of view, pose or colours changes at least this many pixels.
constexpr int kMinChangedPixels = 2000;

TEST_F(ViewerBrowserTest, CanvasIsDrawnWithoutScriptErrors) {
  const json px = Js("occludeViewer.drawnPixels()");
  EXPECT_GT(px["drawn"].get<double>(), kMinDrawnShare * px["total"].get<double>()) << px.dump();
  EXPECT_EQ(Js("document.body.dataset.viewerErrors"), "0");
  EXPECT_TRUE(browser_->Errors().empty()) << json(browser_->Errors()).dump();
  EXPECT_EQ(Js("occludeViewer.state().triangles"),
            json({fixture_->lower.mesh.num_triangles(), fixture_->upper.mesh.num_triangles()}));
  EXPECT_EQ(Js("document.querySelectorAll('#occlude-viewer-proposals button').length"), 3);
}

// The browser's own screenshot (not the page's readback): inside the canvas's box, the
// pixels that differ from the page's background colour (0xf4f4f2) by more than a little.
TEST_F(ViewerBrowserTest, TheScreenshotShowsTheJawsOnTheCanvas) {
  const json box = Js(R"js((() => {
      const r = document.getElementById('occlude-viewer-canvas').getBoundingClientRect();
      return [Math.ceil(r.left), Math.ceil(r.top), Math.floor(r.width), Math.floor(r.height)];
    })())js");
  const std::string png = browser_->Screenshot();
  const cv::Mat shot =
      cv::imdecode(cv::Mat(1, static_cast<int>(png.size()), CV_8U, const_cast<char*>(png.data())),
                   cv::IMREAD_COLOR);
  ASSERT_FALSE(shot.empty()) << "the screenshot is not a PNG";
  const cv::Rect canvas(box[0], box[1], box[2], box[3]);
  ASSERT_EQ(canvas & cv::Rect(0, 0, shot.cols, shot.rows), canvas) << box.dump();
  int drawn = 0;
  for (int y = canvas.y + 2; y < canvas.br().y - 2; ++y) {  // inside the canvas's border
    for (int x = canvas.x + 2; x < canvas.br().x - 2; ++x) {
      const cv::Vec3b bgr = shot.at<cv::Vec3b>(y, x);
      drawn += std::abs(bgr[2] - 0xf4) + std::abs(bgr[1] - 0xf4) + std::abs(bgr[0] - 0xf2) > 6;
    }
  }
  EXPECT_GT(drawn, kMinDrawnShare * canvas.area()) << drawn << " of " << canvas.area();
}

TEST_F(ViewerBrowserTest, SwitchingProposalsChangesPoseColoursAndNumbers) {
  Js("occludeViewer.takeSnapshot()");
  Js("document.querySelectorAll('#occlude-viewer-proposals button')[1].click()");
  EXPECT_EQ(Js("document.body.dataset.viewerProposal"), "1");
  EXPECT_GT(Js("occludeViewer.changedSinceSnapshot()").get<int>(), kMinChangedPixels);
  EXPECT_EQ(Js("document.querySelector('#occlude-viewer-numbers caption').textContent"),
            "proposal 2");
  EXPECT_EQ(Js("document.querySelector('#occlude-viewer-numbers th').textContent"),
            "contact area (mm²)");
  Js("occludeViewer.takeSnapshot(); occludeViewer.setProposal(2)");
  EXPECT_GT(Js("occludeViewer.changedSinceSnapshot()").get<int>(), kMinChangedPixels);
  EXPECT_TRUE(browser_->Errors().empty()) << json(browser_->Errors()).dump();
}

TEST_F(ViewerBrowserTest, StandardViewsAndTheUpperJawModesDrawDifferentPictures) {
  std::vector<std::uint32_t> sums;
  for (const char* view : {"occlusal-lower", "occlusal-upper", "frontal", "right", "left"}) {
    Js(std::string("document.querySelector('[data-view=\"") + view + "\"]').click()");
    const json px = Js("occludeViewer.drawnPixels()");
    EXPECT_GT(px["drawn"].get<double>(), kMinDrawnShare * px["total"].get<double>()) << view;
    sums.push_back(px["checksum"]);
  }
  for (std::size_t i = 0; i < sums.size(); ++i) {
    for (std::size_t j = i + 1; j < sums.size(); ++j) EXPECT_NE(sums[i], sums[j]) << i << j;
  }
  Js("occludeViewer.setView('frontal'); occludeViewer.takeSnapshot()");
  Js("occludeViewer.setUpperMode('transparent')");
  EXPECT_GT(Js("occludeViewer.changedSinceSnapshot()").get<int>(), kMinChangedPixels);
  Js("occludeViewer.takeSnapshot(); occludeViewer.setUpperMode('hidden')");
  EXPECT_GT(Js("occludeViewer.changedSinceSnapshot()").get<int>(), kMinChangedPixels);
  EXPECT_EQ(Js("occludeViewer.state().upper"), "hidden");
}

// The display distance the page should read at p_L on the lower jaw: the per-vertex codes
// interpolated on the closest display triangle; sets `tooth` to its FDI number.
double ExpectedLowerDistance(const test::ViewerFixture& f, int proposal, const Eigen::Vector3d& p_L,
                             int* fdi) {
  const io::TriangleMesh& m = f.lower.mesh;
  collision::TrianglePoint best;
  std::size_t best_t = 0;
  best.squared_distance = 1e300;
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto tp =
        collision::ClosestPointOnTriangle(p_L, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2));
    if (tp.squared_distance < best.squared_distance) best = tp, best_t = t;
  }
  const int universal = m.parts[m.triangle_part[best_t]].tooth_number;
  *fdi = universal > 0 ? io::FdiFromUniversal(universal) : 0;
  double d = 0;
  for (int k = 0; k < 3; ++k) {
    const float mm = f.inputs.proposals[proposal].lower_distance_mm[m.triangles[best_t][k]];
    d += best.barycentric[k] * viewer_detail::DistanceCode(mm) / 1000.0;
  }
  return d;
}

TEST_F(ViewerBrowserTest, AClickOnTheLowerJawReadsTheDistanceAndTheTooth) {
  Js("occludeViewer.setView('occlusal-lower')");
  // A canvas pixel on a tooth of the lower jaw (found through the page's own pick).
  const json spot = Js(R"js((() => {
      const c = document.getElementById('occlude-viewer-canvas'), r = c.getBoundingClientRect();
      for (let y = 0.3; y < 0.8; y += 0.02) for (let x = 0.1; x < 0.9; x += 0.02) {
        const hit = occludeViewer.pickAt(x * r.width, y * r.height);
        if (hit.hit && hit.tooth_fdi > 0 && !hit.far) return {x: r.left + x * r.width, y: r.top + y * r.height};
      }
      return null; })())js");
  ASSERT_FALSE(spot.is_null()) << "no lower tooth found on the canvas";
  Js("occludeViewer.pickAt(0, 0)");  // forget it: the click must make the reading itself
  browser_->Click(spot["x"], spot["y"]);
  const json pick = Js("occludeViewer.state().pick");
  ASSERT_TRUE(pick["hit"].get<bool>()) << pick.dump();
  EXPECT_EQ(pick["jaw"], "lower");
  const Eigen::Vector3d p_L(pick["point_L"][0], pick["point_L"][1], pick["point_L"][2]);
  int fdi = 0;
  const double expected = ExpectedLowerDistance(*fixture_, 0, p_L, &fdi);
  EXPECT_NEAR(pick["distance_mm"].get<double>(), expected, 1e-4) << pick.dump();
  EXPECT_EQ(pick["tooth_fdi"], fdi);
  const std::string text = Js("document.getElementById('occlude-viewer-pick').textContent");
  EXPECT_NE(text.find("tooth " + std::to_string(fdi)), std::string::npos) << text;
}

TEST_F(ViewerBrowserTest, ThePageRequestsNothingFromTheNetwork) {
  Js("occludeViewer.setProposal(1); occludeViewer.setView('left')");
  ASSERT_FALSE(browser_->Requests().empty());  // the page itself
  for (const std::string& url : browser_->Requests()) {
    EXPECT_TRUE(url.rfind("file://", 0) == 0 || url.rfind("data:", 0) == 0) << url;
  }
}

}  // namespace
}  // namespace occlude::app
