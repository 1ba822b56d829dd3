// `occlude refine CONFIG --watch --serve PORT` through the real binary on the smallest
// synthetic case: it serves the live 3D page and its event stream on 127.0.0.1, pushes a
// `proposal` event with the new pose after a save of the config, and Ctrl-C (SIGINT) stops
// it with exit code 0, the port freed and no half-written output; in headless Chromium the
// page redraws after the save (skipped, saying why, where no browser can run).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

#include "case_run.h"
#include "headless_browser.h"
#include "loopback_client.h"
#include "test_common.h"

namespace occlude::app {
namespace {

using Clock = std::chrono::steady_clock;

// Building the oracle and the first refinement of the 5000-triangle pair takes seconds
// (more under the sanitizer); every wait here gives up after this.
constexpr std::chrono::seconds kPatience{120};

std::string ServeConfig(const std::filesystem::path& out, double adjust_x_mm) {
  return "[synthetic]\ntriangles = 5000\n[accuracy]\nvoxel_mm = 1.0\n[report]\n"
         "image_width_px = 300\n[adjust]\ntranslation_mm = [" +
         std::to_string(adjust_x_mm) + ", 0.0, 0.0]\n[output]\nfolder = \"" + out.string() + "\"\n";
}

std::string FileText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// `occlude refine CONFIG --from-config --watch --serve 0` in a child process, its stdout and
// stderr in a log file; the port it printed. Interrupted (SIGINT) and reaped by the end.
class ServingRefine {
 public:
  explicit ServingRefine(const test::TempDir& tmp) : log_(tmp / "refine.log") {
    const std::string config = (tmp / "case.toml").string();
    pid_ = ::fork();
    if (pid_ == 0) {
      const int fd = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::execl(OCCLUDE_BINARY, OCCLUDE_BINARY, "refine", config.c_str(), "--from-config", "--watch",
              "--serve", "0", static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  ~ServingRefine() {
    if (pid_ > 0 && !reaped_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  // Waits for the "live page at http://127.0.0.1:PORT/" line; 0 when it does not come.
  int WaitForPort() {
    const std::regex url("live page at http://127\\.0\\.0\\.1:([0-9]+)/");
    for (const auto deadline = Clock::now() + kPatience; Clock::now() < deadline;) {
      std::smatch m;
      const std::string text = log();
      if (std::regex_search(text, m, url) && text.find("watching") != std::string::npos) {
        return std::stoi(m[1]);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return 0;
  }
  // SIGINT, then the exit status (-1 when it did not exit normally within the patience).
  int Interrupt() {
    ::kill(pid_, SIGINT);
    for (const auto deadline = Clock::now() + kPatience; Clock::now() < deadline;) {
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        reaped_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return -1;
  }
  std::string log() const { return FileText(log_); }

 private:
  std::filesystem::path log_;
  pid_t pid_ = -1;
  bool reaped_ = false;
};

// The data of the last `proposal` event in `stream` with "save": `save`, as JSON.
json ProposalEvent(const std::string& stream, int save) {
  json found;
  std::istringstream lines(stream);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("data: ", 0) != 0) continue;
    const json data = json::parse(line.substr(6), nullptr, false);
    if (data.is_object() && data["numbers"]["save"] == save) found = data;
  }
  return found;
}

TEST(RefineServeTest, ServesThePagePushesTheNewPoseAfterASaveAndStopsOnSigint) {
  test::TempDir tmp;
  Write(tmp / "case.toml", ServeConfig(tmp / "out", 0.1));
  ServingRefine refine(tmp);
  const int port = refine.WaitForPort();
  ASSERT_GT(port, 0) << refine.log();

  test::LoopbackClient page(port);
  ASSERT_TRUE(page.connected());
  page.Send("GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  const std::string html = page.ReadAll();
  EXPECT_EQ(html.rfind("HTTP/1.1 200", 0), 0u) << html.substr(0, 200);
  EXPECT_NE(html.find("id=\"occlude-viewer-canvas\""), std::string::npos);
  EXPECT_NE(html.find("\"live\":\"/events\""), std::string::npos);

  test::LoopbackClient events(port, kPatience);
  ASSERT_TRUE(events.connected());
  events.Send("GET /events HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a new modification time
  Write(tmp / "case.toml", ServeConfig(tmp / "out", 0.25));
  const std::string first = events.ReadUntil("\"save\":1");
  const std::string stream = events.ReadUntil("\n\n", first.find("\"save\":1"));  // whole
  const json pushed = ProposalEvent(stream, 1);
  ASSERT_TRUE(pushed.is_object()) << stream.substr(0, 300) << "\n" << refine.log();
  EXPECT_EQ(pushed["label"], "latest refinement");
  EXPECT_EQ(pushed["numbers"]["held"], "tx");
  EXPECT_NE(pushed["numbers"]["moved t (mm)"].get<std::string>().rfind("(0.250,", 0),
            std::string::npos)
      << pushed["numbers"].dump();
  EXPECT_TRUE(pushed["numbers"].contains("contact before (mm\u00b2)"));
  EXPECT_TRUE(pushed["numbers"].contains("contact after (mm\u00b2)"));

  EXPECT_EQ(refine.Interrupt(), 0) << refine.log();
  EXPECT_NE(refine.log().find("stopped (interrupted)"), std::string::npos) << refine.log();
  EXPECT_FALSE(test::LoopbackClient(port).connected()) << "port " << port << " still open";
  for (const auto& entry : std::filesystem::directory_iterator(tmp / "out")) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos)
        << "half-written " << entry.path();  // WriteFileAtomic's temporary names
  }
  EXPECT_TRUE(std::filesystem::exists(tmp / "out" / "report.html"));
}

/// A pushed pose changes at least this many pixels of the canvas.
constexpr int kMinServeChangedPixels = 500;

TEST(RefineServeTest, TheLivePageRedrawsAfterASaveInABrowser) {
  std::string why;
  const auto browser = test::HeadlessBrowser::Launch(&why);
  if (!browser) GTEST_SKIP() << "no headless browser: " << why;
  test::TempDir tmp;
  Write(tmp / "case.toml", ServeConfig(tmp / "out", 0.1));
  ServingRefine refine(tmp);
  const int port = refine.WaitForPort();
  ASSERT_GT(port, 0) << refine.log();
  browser->Navigate("http://127.0.0.1:" + std::to_string(port) + "/");
  ASSERT_TRUE(
      browser->WaitFor("document.body.dataset.viewerReady === '1' && "
                       "document.body.dataset.viewerLive === 'open'",
                       60))
      << json(browser->Errors()).dump();
  browser->Evaluate("occludeViewer.takeSnapshot()");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a new modification time
  Write(tmp / "case.toml", ServeConfig(tmp / "out", 0.6));
  ASSERT_TRUE(browser->WaitFor("document.body.dataset.viewerUpdates === '1'", 60)) << refine.log();
  EXPECT_GT(browser->Evaluate("occludeViewer.changedSinceSnapshot()").get<int>(),
            kMinServeChangedPixels);
  EXPECT_EQ(browser->Evaluate("occludeViewer.state().proposals"), 1);  // replaced, not added
  EXPECT_EQ(browser->Evaluate("document.body.dataset.viewerErrors"), "0");
  EXPECT_TRUE(browser->Errors().empty()) << json(browser->Errors()).dump();
  EXPECT_EQ(refine.Interrupt(), 0) << refine.log();
  EXPECT_TRUE(browser->WaitFor("document.body.dataset.viewerLive === 'closed'", 30));
}

}  // namespace
}  // namespace occlude::app
