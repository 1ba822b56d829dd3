// report.html of `propose` (ProposeAndReport on the 5,000-triangle synthetic pair, two
// distinct proposals) in headless Chromium: the 3D view's canvas is present and drawn, no
// script error, switching to proposal 2 changes the picture and lists its clinical
// relationships, the still images stay, and the
// page requests nothing from the network. Skips, saying why, where no browser can run.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "config/case_config.h"
#include "headless_browser.h"
#include "report/proposal_report.h"
#include "test_common.h"

namespace occlude::app {
namespace {

using nlohmann::json;

// Two proposals from three Ceres starts: distinct at a small separation (they are seats
// millimetres apart, so the picture changes between them).
constexpr const char* kProposeConfig =
    "[synthetic]\ntriangles = 5000\n[accuracy]\nvoxel_mm = 1.0\n[report]\nimage_width_px = 300\n"
    "[solver]\nname = \"ceres\"\nstarts = 3\nproposals = 3\nthreads = 1\n[solver.options]\n"
    "distinct_translation_mm = 0.01\ndistinct_rotation_deg = 0.05\n[start]\n"
    "translation_mm = [0.4, 0.5, -0.3]\nrotation_deg = [0.5, -0.8, 0.4]\n[output]\n"
    "folder = \"out\"\n";

/// A drawn canvas covers at least this share of its pixels with the jaws.
constexpr double kMinReportDrawnShare = 0.05;
/// Switching proposals changes at least this many pixels.
constexpr int kMinProposalChangedPixels = 2000;

TEST(ReportPageBrowserTest, TheProposeReportDrawsAndSwitchesProposals) {
  std::string why;
  const auto browser = test::HeadlessBrowser::Launch(&why);
  if (!browser) GTEST_SKIP() << "no headless browser: " << why;
  test::TempDir tmp;
  std::ofstream(tmp / "case.toml") << kProposeConfig;
  ProposeAndReport(LoadCaseConfig(tmp / "case.toml"), "", 0);
  browser->Navigate("file://" + (tmp / "out" / "report.html").string());
  ASSERT_TRUE(browser->WaitFor("document.body.dataset.viewerReady === '1'", 60))
      << json(browser->Errors()).dump();
  const json px = browser->Evaluate("occludeViewer.drawnPixels()");
  EXPECT_GT(px["drawn"].get<double>(), kMinReportDrawnShare * px["total"].get<double>())
      << px.dump();
  EXPECT_EQ(browser->Evaluate("document.body.dataset.viewerErrors"), "0");
  const int proposals =
      browser->Evaluate("document.querySelectorAll('#occlude-viewer-proposals button').length");
  ASSERT_GE(proposals, 2);
  browser->Evaluate("occludeViewer.takeSnapshot(); occludeViewer.setProposal(1)");
  EXPECT_EQ(browser->Evaluate("document.body.dataset.viewerProposal"), "1");
  EXPECT_GT(browser->Evaluate("occludeViewer.changedSinceSnapshot()").get<int>(),
            kMinProposalChangedPixels);
  EXPECT_EQ(browser->Evaluate("document.querySelector('#occlude-viewer-numbers caption')"
                              ".textContent"),
            "proposal 2");
  // Beside proposal 2: its clinical relationships, as proposals.json gives them.
  const json listed = browser->Evaluate(
      "Object.fromEntries(Array.from(document.querySelectorAll('#occlude-viewer-numbers tr'))"
      ".map(function(tr) { return [tr.cells[0].textContent, tr.cells[1].textContent]; }))");
  json proposals_json;
  std::ifstream(tmp / "out" / "proposals.json") >> proposals_json;
  const json& overjet = proposals_json["proposals"][1]["relationships"]["overjet_mm"];
  ASSERT_TRUE(listed.contains("overjet")) << listed.dump();
  ASSERT_TRUE(listed.contains("molar relationship, right")) << listed.dump();
  if (overjet.is_number()) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f mm", overjet.get<double>());
    EXPECT_EQ(listed["overjet"].get<std::string>().rfind(text, 0), 0u)
        << listed["overjet"] << " vs " << overjet;
  }
  EXPECT_EQ(browser->Evaluate("document.querySelectorAll('figure img').length"), 4);
  EXPECT_TRUE(browser->Errors().empty()) << json(browser->Errors()).dump();
  for (const std::string& url : browser->Requests()) {
    EXPECT_TRUE(url.rfind("file://", 0) == 0 || url.rfind("data:", 0) == 0) << url;
  }
}

}  // namespace
}  // namespace occlude::app
