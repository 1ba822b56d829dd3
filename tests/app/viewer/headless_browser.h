// A headless Chromium driven over the DevTools protocol (--remote-debugging-pipe),
// for the tests and measurements of the 3D viewer: open a page, evaluate script in
// it, click, take a screenshot, and read the console errors, exceptions and network
// requests the page made. Debian's `chromium` (or $OCCLUDE_CHROMIUM); WebGL through
// SwiftShader. The browser runs in its own process group with a fresh profile
// folder, resolves no host name, and is closed (then killed if it must be) with the
// object.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <deque>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace occlude::test {

/// The command-line switches the browser is started with (besides the profile folder).
std::vector<std::string> HeadlessChromiumFlags();

class HeadlessBrowser {
 public:
  /// Starts the browser and opens a blank page; nullptr with `why` set when no browser
  /// can run here (none installed, or it does not answer within `timeout_s`).
  static std::unique_ptr<HeadlessBrowser> Launch(std::string* why, double timeout_s = 120);
  ~HeadlessBrowser();
  HeadlessBrowser(const HeadlessBrowser&) = delete;
  HeadlessBrowser& operator=(const HeadlessBrowser&) = delete;

  /// Opens `url` and waits for its load event. Throws std::runtime_error on a timeout.
  void Navigate(const std::string& url, double timeout_s = 60);
  /// The value of a script expression in the page (promises awaited), as JSON. Throws
  /// std::runtime_error with the message when the script throws.
  nlohmann::json Evaluate(const std::string& expression, double timeout_s = 60);
  /// Evaluates `expression` every 50 ms until it is truthy; false after `timeout_s`.
  bool WaitFor(const std::string& expression, double timeout_s);
  /// A left click (press and release) at CSS pixel (x, y) of the viewport.
  void Click(double x, double y);
  /// PNG bytes of the viewport.
  std::string Screenshot();

  /// CPU seconds (user + system) used so far by the browser's processes that are still
  /// running (its process group, read from /proc); for measurements on a shared machine.
  double CpuSeconds() const;

  /// Console errors and uncaught exceptions reported since the last Navigate.
  const std::vector<std::string>& Errors() const { return errors_; }
  /// URLs the page requested since the last Navigate (the page's own included).
  const std::vector<std::string>& Requests() const { return requests_; }

 private:
  HeadlessBrowser() = default;
  nlohmann::json Call(const std::string& method, const nlohmann::json& params, double timeout_s,
                      bool in_page = true);
  void Send(const nlohmann::json& message);
  /// Reads one message (true) or times out (false) at `deadline`.
  bool Receive(std::chrono::steady_clock::time_point deadline, nlohmann::json* message);
  void Record(const nlohmann::json& event);
  void Close();

  pid_t pid_ = -1;
  int to_browser_ = -1;
  int from_browser_ = -1;
  std::string pending_;  ///< bytes read but not yet split into messages
  int next_id_ = 1;
  std::string session_;  ///< the page's DevTools session
  std::deque<nlohmann::json> events_;
  std::vector<std::string> errors_;
  std::vector<std::string> requests_;
  std::filesystem::path profile_;
};

/// Decodes standard base64 (as DevTools sends screenshots).
std::string DecodeBase64(const std::string& text);

}  // namespace occlude::test
