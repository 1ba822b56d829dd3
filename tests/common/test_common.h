// Shared test helpers: the real-data folder, temporary folders, small meshes,
// and named tolerances.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "occlude/io/triangle_mesh.h"

namespace occlude::test {

/// `../shared/data` (or $OCCLUDE_DATA_DIR) when it exists, else nullopt.
std::optional<std::filesystem::path> SharedDataDir();

/// A case folder under SharedDataDir()/cases, or nullopt when absent.
std::optional<std::filesystem::path> SharedCase(const std::string& name);

/// A fresh, empty temporary folder, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// Runs `body` as an unprivileged user and returns its result: directly when this
/// process is not root; as root, in a forked child that switches to the user
/// nobody (uid and gid 65534) first, so that file permissions apply (root reads
/// and writes anything). nullopt when the switch is impossible; `why` then says why.
std::optional<std::string> RunUnprivileged(const std::function<std::string()>& body,
                                           std::string* why);

/// Axis-aligned closed box [lo, hi] as 12 outward-facing triangles, one part.
io::TriangleMesh MakeBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
/// Closed UV sphere (outward), `rings` >= 3, `segments` >= 3.
io::TriangleMesh MakeSphere(const Eigen::Vector3d& center, double radius, int rings, int segments);

/// Tolerance for quantities that are exact up to double rounding on mm-sized inputs.
inline constexpr double kExactMm = 1e-9;

}  // namespace occlude::test

/// Skips the current test, saying why, when the shared real-data folder is absent.
#define OCCLUDE_REQUIRE_CASE(var, name)                               \
  const auto var##_opt = ::occlude::test::SharedCase(name);           \
  if (!var##_opt)                                                     \
    GTEST_SKIP() << "shared data case '" << (name) << "' not found (" \
                 << "set OCCLUDE_DATA_DIR or place ../shared/data)";  \
  const std::filesystem::path var = *var##_opt
