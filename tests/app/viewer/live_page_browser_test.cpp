// The live server (app/serve) with a real browser: a page served on 127.0.0.1
// opens an EventSource on /events and shows each published event, as the live
// refinement page will. Skips, saying why, where no browser can run.
#include <gtest/gtest.h>

#include "headless_browser.h"
#include "serve/live_server.h"

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

}  // namespace
}  // namespace occlude::app
