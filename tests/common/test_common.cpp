// Implementation of the shared test helpers.
#include "test_common.h"

#include <grp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <stdexcept>

namespace occlude::test {

std::optional<std::filesystem::path> SharedDataDir() {
  std::filesystem::path dir = OCCLUDE_SHARED_DATA_DIR;
  if (const char* env = std::getenv("OCCLUDE_DATA_DIR")) dir = env;
  std::error_code ec;
  if (std::filesystem::is_directory(dir, ec)) return dir;
  return std::nullopt;
}

std::optional<std::filesystem::path> SharedCase(const std::string& name) {
  const auto root = SharedDataDir();
  if (!root) return std::nullopt;
  const auto dir = *root / "cases" / name;
  std::error_code ec;
  if (std::filesystem::exists(dir / "upper.stl", ec)) return dir;
  return std::nullopt;
}

std::optional<std::string> RunUnprivileged(const std::function<std::string()>& body,
                                           std::string* why) {
  if (::geteuid() != 0) return body();
  int fds[2];
  if (::pipe(fds) != 0) {
    *why = "pipe() failed";
    return std::nullopt;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    *why = "fork() failed";
    return std::nullopt;
  }
  constexpr uid_t kNobody = 65534;
  if (pid == 0) {  // child: drop root for good, run, send the result, exit
    ::close(fds[0]);
    const std::string failed(1, '\x01'), passed(1, '\x02');
    std::string result = failed + "cannot switch to uid/gid 65534 (nobody)";
    if (::setgroups(0, nullptr) == 0 && ::setgid(kNobody) == 0 && ::setuid(kNobody) == 0) {
      try {
        result = passed + body();
      } catch (const std::exception& e) {
        result = failed + "the body threw: " + e.what();
      }
    }
    std::size_t done = 0;
    while (done < result.size()) {
      const ssize_t n = ::write(fds[1], result.data() + done, result.size() - done);
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string out;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;)
    out.append(buffer, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  if (out.empty() || out[0] != '\x02') {
    *why = out.empty() ? "the unprivileged child died" : out.substr(1);
    return std::nullopt;
  }
  return out.substr(1);
}

TempDir::TempDir() {
  std::random_device rd;
  const auto base = std::filesystem::temp_directory_path();
  for (int attempt = 0; attempt < 100; ++attempt) {
    path_ = base / ("occlude-test-" + std::to_string(rd()));
    std::error_code ec;
    if (std::filesystem::create_directory(path_, ec)) return;
  }
  throw std::runtime_error("cannot create a temporary folder under " + base.string());
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

io::TriangleMesh MakeBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  io::TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(),
                            (i & 4) ? hi.z() : lo.z());
  }
  // Two CCW (outward) triangles per face.
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    m.triangles.emplace_back(f[0], f[1], f[2]);
    m.triangles.emplace_back(f[0], f[2], f[3]);
  }
  m.parts.push_back({"box", 0});
  m.triangle_part.assign(m.triangles.size(), 0);
  m.ComputeFaceNormals();
  return m;
}

io::TriangleMesh MakeSphere(const Eigen::Vector3d& center, double radius, int rings, int segments) {
  io::TriangleMesh m;
  const double pi = std::acos(-1.0);
  m.vertices.push_back(center + Eigen::Vector3d(0, 0, radius));
  for (int r = 1; r < rings; ++r) {
    const double theta = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * pi * s / segments;
      m.vertices.push_back(center + radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                             std::sin(theta) * std::sin(phi),
                                                             std::cos(theta)));
    }
  }
  m.vertices.push_back(center - Eigen::Vector3d(0, 0, radius));
  const int south = static_cast<int>(m.vertices.size()) - 1;
  auto ring_vertex = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s)
    m.triangles.emplace_back(0, ring_vertex(1, s), ring_vertex(1, s + 1));
  for (int r = 1; r < rings - 1; ++r) {
    for (int s = 0; s < segments; ++s) {
      m.triangles.emplace_back(ring_vertex(r, s), ring_vertex(r + 1, s), ring_vertex(r + 1, s + 1));
      m.triangles.emplace_back(ring_vertex(r, s), ring_vertex(r + 1, s + 1), ring_vertex(r, s + 1));
    }
  }
  for (int s = 0; s < segments; ++s) {
    m.triangles.emplace_back(south, ring_vertex(rings - 1, s + 1), ring_vertex(rings - 1, s));
  }
  m.parts.push_back({"sphere", 0});
  m.triangle_part.assign(m.triangles.size(), 0);
  m.ComputeFaceNormals();
  return m;
}

}  // namespace occlude::test
