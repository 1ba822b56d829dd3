// Runs the real `occlude` binary (OCCLUDE_BINARY, injected by CMake) as a user
// would, capturing its exit code and its output.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace occlude::test {

struct CommandRun {
  int exit_code = 0;
  std::string output;  // stdout + stderr
};

inline CommandRun OccludeWithPrefix(const std::string& prefix, const std::string& args);

inline CommandRun Occlude(const std::string& args) { return OccludeWithPrefix("", args); }

/// What to put before OCCLUDE_BINARY so that it runs unprivileged: "" when this
/// process is not root; as root, setpriv switching to the user nobody (file
/// permissions do not bind root). nullopt, with `why`, when that does not work
/// here (no setpriv, or nobody cannot reach the binary).
inline std::optional<std::string> UnprivilegedPrefix(std::string* why) {
  if (::geteuid() != 0) return std::string();
  const std::string prefix = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
  const std::string probe = prefix + OCCLUDE_BINARY + " --version >/dev/null 2>&1";
  if (std::system(probe.c_str()) != 0) {
    *why = "'" + prefix +
           "occlude --version' fails (no setpriv, or the user nobody cannot reach the binary)";
    return std::nullopt;
  }
  return prefix;
}

/// Runs the binary as the user nobody (see UnprivilegedPrefix; `prefix` from it).
inline CommandRun OccludeWithPrefix(const std::string& prefix, const std::string& args) {
  const std::string cmd = prefix + std::string(OCCLUDE_BINARY) + " " + args + " 2>&1";
  CommandRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return {-1, "popen failed"};
  char buf[4096];
  std::size_t n = 0;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// `args` with every "{T}" replaced by `dir`.
inline std::string WithFolder(std::string args, const std::filesystem::path& dir) {
  for (std::size_t at; (at = args.find("{T}")) != std::string::npos;) {
    args.replace(at, 3, dir.string());
  }
  return args;
}

/// A failed run's output is one line, "occlude: error: ...", holding `expected`.
inline void ExpectOneErrorLine(const CommandRun& r, const std::string& expected) {
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.rfind("occlude: error: ", 0), 0u) << r.output;
}

inline bool EmptyOrMissing(const std::filesystem::path& dir) {
  std::error_code ec;
  return !std::filesystem::exists(dir, ec) || std::filesystem::is_empty(dir, ec);
}

}  // namespace occlude::test
