// The live server (app/serve) with a real browser: a page served on 127.0.0.1
// opens an EventSource on /events and shows each published event, and the live
// viewer page (ViewerInputs::live_events_path) redraws with each proposal pushed
// to it, as the live refinement page will. Skips, saying why, where no browser
// can run.
#include <gtest/gtest.h>

#include "headless_browser.h"
#include "serve/live_server.h"
#include "viewer_fixture.h"

namespace occlude::app {
namespace {

constexpr const char* kLivePage = R"html(<!DOCTYPE html><html><body><p id="last">none</p>
<script>
const source = new EventSource('/events');
source.addEventListener('refined', (e) => {
  document.getElementById('last').textContent = e.data;
  document.body.dataset.events = String(Number(document.body.dataset.events || 0) + 1);
});
source.onopen = () => { document.body.dataset.open = '1'; };
</script></body></html>)html";

TEST(LivePageBrowserTest, AnEventPublishedReachesTheOpenPage) {
  std::string why;
  const auto browser = test::HeadlessBrowser::Launch(&why);
  if (!browser) GTEST_SKIP() << "no headless browser: " << why;
  LiveServer server({});
  server.SetPage(kLivePage);
  browser->Navigate(server.url());
  ASSERT_TRUE(browser->WaitFor("document.body.dataset.open === '1'", 30));
  ASSERT_EQ(server.clients(), 1u);
  server.Publish("refined", "{\"step\": 1,\n\"area\": 13.2}");
  ASSERT_TRUE(browser->WaitFor("document.body.dataset.events === '1'", 30));
  EXPECT_EQ(browser->Evaluate("document.getElementById('last').textContent"),
            "{\"step\": 1,\n\"area\": 13.2}");
  server.Publish("refined", "second");
  ASSERT_TRUE(browser->WaitFor("document.body.dataset.events === '2'", 30));
  EXPECT_EQ(browser->Evaluate("document.getElementById('last').textContent"), "second");
  EXPECT_TRUE(browser->Errors().empty()) << nlohmann::json(browser->Errors()).dump();
  for (const std::string& url : browser->Requests()) {
    EXPECT_EQ(url.rfind("http://127.0.0.1:", 0), 0u) << url;
  }
}

/// A pushed pose and colours change at least this many pixels of the canvas.
constexpr int kMinPushChangedPixels = 2000;

TEST(LivePageBrowserTest, TheLiveViewerRedrawsWithEachProposalPushed) {
  std::string why;
  const auto browser = test::HeadlessBrowser::Launch(&why);
  if (!browser) GTEST_SKIP() << "no headless browser: " << why;
  auto f = test::MakeSyntheticViewer(3);
  std::vector<ViewerProposal> later(f->inputs.proposals.begin() + 1, f->inputs.proposals.end());
  f->inputs.proposals.resize(1);  // the page opens on the start; refinements arrive later
  f->inputs.live_events_path = "/events";
  LiveServer server({});
  server.SetPage(ViewerPage(f->inputs));
  browser->Navigate(server.url());
  ASSERT_TRUE(
      browser->WaitFor("document.body.dataset.viewerReady === '1' && "
                       "document.body.dataset.viewerLive === 'open'",
                       60))
      << nlohmann::json(browser->Errors()).dump();
  browser->Evaluate("occludeViewer.takeSnapshot()");
  later[0].label = "refined";
  server.Publish("proposal", ViewerProposalEvent(f->inputs, later[0]));
  ASSERT_TRUE(browser->WaitFor("document.body.dataset.viewerUpdates === '1'", 30));
  EXPECT_EQ(browser->Evaluate("[occludeViewer.state().proposal, occludeViewer.state().proposals]"),
            nlohmann::json({1, 2}));
  EXPECT_GT(browser->Evaluate("occludeViewer.changedSinceSnapshot()").get<int>(),
            kMinPushChangedPixels);
  // The same label again replaces that proposal rather than adding one.
  browser->Evaluate("occludeViewer.takeSnapshot()");
  later[1].label = "refined";
  server.Publish("proposal", ViewerProposalEvent(f->inputs, later[1]));
  ASSERT_TRUE(browser->WaitFor("document.body.dataset.viewerUpdates === '2'", 30));
  EXPECT_EQ(browser->Evaluate("occludeViewer.state().proposals"), 2);
  EXPECT_GT(browser->Evaluate("occludeViewer.changedSinceSnapshot()").get<int>(),
            kMinPushChangedPixels);
  EXPECT_EQ(browser->Evaluate("document.querySelector('#occlude-viewer-numbers caption')"
                              ".textContent"),
            "refined");
  EXPECT_TRUE(browser->Errors().empty()) << nlohmann::json(browser->Errors()).dump();
  server.Stop();
  EXPECT_TRUE(browser->WaitFor("document.body.dataset.viewerLive === 'closed'", 30));
}

}  // namespace
}  // namespace occlude::app
