// The DevTools-pipe driver of headless Chromium (see headless_browser.h). Messages
// are JSON texts ended by a NUL byte: commands on the browser's fd 3, answers and
// events on its fd 4.
#include "headless_browser.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace occlude::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using nlohmann::json;

Clock::time_point After(double seconds) {
  return Clock::now() +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

// $OCCLUDE_CHROMIUM, else the first chromium on PATH; empty when there is none.
std::string FindChromium() {
  if (const char* env = std::getenv("OCCLUDE_CHROMIUM"); env != nullptr && *env != '\0') {
    return env;
  }
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    for (const char* name : {"chromium", "chromium-browser"}) {
      const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
      if (!candidate.parent_path().empty() && ::access(candidate.c_str(), X_OK) == 0) {
        return candidate.string();
      }
    }
    start = end + 1;
  }
  return "";
}

// In the child: fds 3 and 4 become the pipe ends, output goes to `log_fd`; never returns.
// Only async-signal-safe calls (the test process may have threads).
[[noreturn]] void ExecBrowser(char* const* argv, int commands, int answers, int log_fd) {
  ::setpgid(0, 0);
  const int in = ::fcntl(commands, F_DUPFD, 10);  // out of the way of 3 and 4
  const int out = ::fcntl(answers, F_DUPFD, 10);
  ::dup2(in, 3);
  ::dup2(out, 4);
  if (log_fd >= 0) {
    ::dup2(log_fd, 1);
    ::dup2(log_fd, 2);
  }
  ::execv(argv[0], argv);
  ::_exit(127);
}

std::string Describe(const json& remote_object) {
  if (remote_object.contains("value")) return remote_object["value"].dump();
  return remote_object.value("description", remote_object.value("type", std::string("?")));
}

}  // namespace

std::vector<std::string> HeadlessChromiumFlags() {
  return {"--headless", "--no-sandbox", "--disable-gpu",
          // WebGL on the CPU; without the second switch Chromium still falls back to
          // SwiftShader but logs that the automatic fallback is deprecated.
          "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
          "--disable-background-networking", "--disable-component-update", "--disable-sync",
          "--no-first-run", "--no-default-browser-check", "--disable-extensions",
          "--disable-default-apps", "--disable-dev-shm-usage",
          // No host name resolves: without it Chromium looks up its update servers even
          // with --disable-background-networking and --disable-component-update.
          "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1", "--mute-audio",
          "--hide-scrollbars", "--window-size=1200,900", "--remote-debugging-pipe"};
}

std::unique_ptr<HeadlessBrowser> HeadlessBrowser::Launch(std::string* why, double timeout_s) {
  const std::string exe = FindChromium();
  if (exe.empty()) {
    *why = "no chromium on PATH (Debian: apt-get install chromium; or set OCCLUDE_CHROMIUM)";
    return nullptr;
  }
  std::unique_ptr<HeadlessBrowser> b(new HeadlessBrowser());
  char folder[] = "/tmp/occlude-chromium-XXXXXX";
  if (::mkdtemp(folder) == nullptr) {
    *why = std::string("cannot create a profile folder: ") + std::strerror(errno);
    return nullptr;
  }
  b->profile_ = folder;
  std::vector<std::string> args = {exe, "--user-data-dir=" + b->profile_.string()};
  for (const std::string& f : HeadlessChromiumFlags()) args.push_back(f);
  int commands[2], answers[2];
  if (::pipe2(commands, O_CLOEXEC) != 0 || ::pipe2(answers, O_CLOEXEC) != 0) {
    *why = std::string("pipe: ") + std::strerror(errno);
    return nullptr;
  }
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const fs::path log = b->profile_ / "chromium.log";
  const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  ::signal(SIGPIPE, SIG_IGN);  // a browser that dies must not kill the test
  b->pid_ = ::fork();
  if (b->pid_ < 0) {
    *why = std::string("fork: ") + std::strerror(errno);
    return nullptr;
  }
  if (b->pid_ == 0) ExecBrowser(argv.data(), commands[0], answers[1], log_fd);
  ::close(commands[0]);
  ::close(answers[1]);
  if (log_fd >= 0) ::close(log_fd);
  b->to_browser_ = commands[1];
  b->from_browser_ = answers[0];
  try {
    const json target = b->Call("Target.createTarget", {{"url", "about:blank"}}, timeout_s, false);
    const json attached =
        b->Call("Target.attachToTarget", {{"targetId", target.at("targetId")}, {"flatten", true}},
                30, false);
    b->session_ = attached.at("sessionId").get<std::string>();
    for (const char* domain : {"Page", "Runtime", "Network", "Log"}) {
      b->Call(std::string(domain) + ".enable", json::object(), 30);
    }
  } catch (const std::exception& e) {
    std::ifstream in(log);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (text.size() > 400) text = "..." + text.substr(text.size() - 400);
    for (char& c : text) c = c == '\n' ? ' ' : c;
    *why = exe + " did not start a headless page (" + e.what() + "; its output: " + text + ")";
    return nullptr;
  }
  return b;
}

HeadlessBrowser::~HeadlessBrowser() { Close(); }

void HeadlessBrowser::Close() {
  if (pid_ > 0) {
    try {
      Send({{"id", next_id_++}, {"method", "Browser.close"}});
    } catch (const std::exception&) {  // the browser is gone already
    }
    const auto deadline = After(10);
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0 && Clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ::kill(-pid_, SIGKILL);  // its own process group: whatever of it is left
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
  }
  for (int* fd : {&to_browser_, &from_browser_}) {
    if (*fd >= 0) ::close(*fd);
    *fd = -1;
  }
  std::error_code ec;
  if (!profile_.empty()) fs::remove_all(profile_, ec);
}

void HeadlessBrowser::Send(const json& message) {
  const std::string text = message.dump() + '\0';
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(to_browser_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("the browser closed its command pipe");
    done += static_cast<std::size_t>(n);
  }
}

bool HeadlessBrowser::Receive(Clock::time_point deadline, json* message) {
  for (;;) {
    if (const std::size_t end = pending_.find('\0'); end != std::string::npos) {
      *message = json::parse(pending_.substr(0, end));
      pending_.erase(0, end + 1);
      return true;
    }
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return false;
    pollfd p = {from_browser_, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
    char buffer[1 << 16];
    const ssize_t n = ::read(from_browser_, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("the browser closed its answer pipe");
    pending_.append(buffer, static_cast<std::size_t>(n));
  }
}

void HeadlessBrowser::Record(const json& event) {
  const std::string method = event.value("method", "");
  const json& params = event.contains("params") ? event["params"] : json::object();
  if (method == "Runtime.exceptionThrown") {
    const json& d = params.at("exceptionDetails");
    errors_.push_back("exception: " +
                      (d.contains("exception") ? Describe(d["exception"]) : d.value("text", "")));
  } else if (method == "Runtime.consoleAPICalled" && params.value("type", "") == "error") {
    std::string text = "console.error:";
    for (const json& a : params.value("args", json::array())) text += " " + Describe(a);
    errors_.push_back(text);
  } else if (method == "Log.entryAdded" && params.at("entry").value("level", "") == "error") {
    errors_.push_back("log: " + params.at("entry").value("text", ""));
  } else if (method == "Network.requestWillBeSent") {
    requests_.push_back(params.at("request").value("url", ""));
  } else if (method == "Page.loadEventFired") {
    events_.push_back(event);
  }
}

json HeadlessBrowser::Call(const std::string& method, const json& params, double timeout_s,
                           bool in_page) {
  const int id = next_id_++;
  json message = {{"id", id}, {"method", method}, {"params", params}};
  if (in_page) message["sessionId"] = session_;
  Send(message);
  const auto deadline = After(timeout_s);
  for (json answer; Receive(deadline, &answer);) {
    if (!answer.contains("id")) {
      Record(answer);
    } else if (answer["id"] == id) {
      if (answer.contains("error")) {
        throw std::runtime_error(method + ": " + answer["error"].value("message", "error"));
      }
      return answer.value("result", json::object());
    }
  }
  throw std::runtime_error(method + ": no answer within " + std::to_string(timeout_s) + " s");
}

void HeadlessBrowser::Navigate(const std::string& url, double timeout_s) {
  errors_.clear();
  requests_.clear();
  events_.clear();
  const json result = Call("Page.navigate", {{"url", url}}, timeout_s);
  if (result.contains("errorText")) {
    throw std::runtime_error("cannot open " + url + ": " + result["errorText"].get<std::string>());
  }
  const auto deadline = After(timeout_s);
  for (json event; events_.empty();) {
    if (!Receive(deadline, &event)) throw std::runtime_error(url + ": no load event in time");
    if (!event.contains("id")) Record(event);
  }
}

json HeadlessBrowser::Evaluate(const std::string& expression, double timeout_s) {
  const json r = Call("Runtime.evaluate",
                      {{"expression", expression}, {"returnByValue", true}, {"awaitPromise", true}},
                      timeout_s);
  if (r.contains("exceptionDetails")) {
    const json& d = r["exceptionDetails"];
    throw std::runtime_error(
        expression + ": " +
        (d.contains("exception") ? Describe(d["exception"]) : d.value("text", "")));
  }
  return r.at("result").value("value", json());
}

bool HeadlessBrowser::WaitFor(const std::string& expression, double timeout_s) {
  const auto deadline = After(timeout_s);
  do {
    if (Evaluate("!!(" + expression + ")", timeout_s) == true) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  } while (Clock::now() < deadline);
  return false;
}

void HeadlessBrowser::Click(double x, double y) {
  const json at = {{"x", x}, {"y", y}};
  Call("Input.dispatchMouseEvent", {{"type", "mouseMoved"}, {"x", x}, {"y", y}}, 30);
  for (const char* type : {"mousePressed", "mouseReleased"}) {
    json e = at;
    e["type"] = type;
    e["button"] = "left";
    e["clickCount"] = 1;
    Call("Input.dispatchMouseEvent", e, 30);
  }
}

std::string HeadlessBrowser::Screenshot() {
  return DecodeBase64(Call("Page.captureScreenshot", {{"format", "png"}}, 60).at("data"));
}

double HeadlessBrowser::CpuSeconds() const {
  double ticks = 0;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;  // not a process
    std::ifstream in(entry.path() / "stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t name_end = stat.rfind(')');  // the command name may hold spaces
    if (name_end == std::string::npos) continue;
    std::istringstream fields(stat.substr(name_end + 2));
    std::vector<std::string> f((std::istream_iterator<std::string>(fields)), {});
    // After the name: state ppid pgrp ... utime (11th) stime (12th).
    if (f.size() > 12 && std::stol(f[2]) == pid_) ticks += std::stod(f[11]) + std::stod(f[12]);
  }
  return ticks / static_cast<double>(::sysconf(_SC_CLK_TCK));
}

std::string DecodeBase64(const std::string& text) {
  std::string out;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    int v = -1;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    if (c >= '0' && c <= '9') v = c - '0' + 52;
    if (c == '+') v = 62;
    if (c == '/') v = 63;
    if (v < 0) continue;  // padding and line breaks
    bits = (bits << 6) | static_cast<std::uint32_t>(v);
    if ((count += 6) >= 8) {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xffu);
    }
  }
  return out;
}

}  // namespace occlude::test
