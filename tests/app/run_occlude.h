// Runs the real `occlude` binary (OCCLUDE_BINARY, injected by CMake) as a user
// would, capturing its exit code and its output.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>

namespace occlude::test {

struct CommandRun {
  int exit_code = 0;
  std::string output;  // stdout + stderr
};

inline CommandRun Occlude(const std::string& args) {
  const std::string cmd = std::string(OCCLUDE_BINARY) + " " + args + " 2>&1";
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

inline bool EmptyOrMissing(const std::filesystem::path& dir) {
  std::error_code ec;
  return !std::filesystem::exists(dir, ec) || std::filesystem::is_empty(dir, ec);
}

}  // namespace occlude::test
