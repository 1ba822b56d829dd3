// libFuzzer target: the case config parser (app/config/case_config*.cpp). The
// config names a file in a folder that holds lower.stl and upper.stl (empty:
// the parser only checks that mesh files exist), so inputs can get past the
// mesh keys. Contract: a UserError is the only way to fail, and an accepted
// config has a finite positive voxel size and a finite rigid start pose.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "base/user_error.h"
#include "config/case_config.h"
#include "config/pose_file.h"

namespace {

std::filesystem::path g_config;  // <temporary folder>/case.toml

void Require(bool condition) {
  if (!condition) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("occlude-fuzz-config-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "teeth");
  for (const char* name : {"lower.stl", "upper.stl", "teeth/Tooth_14.stl", "teeth/Tooth_3.stl"}) {
    std::ofstream(dir / name) << "solid x\nendsolid x\n";
  }
  g_config = dir / "case.toml";
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  occlude::app::CaseConfig config;
  try {
    config = occlude::app::ParseCaseConfig(text, g_config);
  } catch (const occlude::app::UserError& e) {
    Require(std::string(e.what()).find('\n') == std::string::npos);  // one line
    return 0;
  }
  const double voxel = config.VoxelSizeMm();
  Require(std::isfinite(voxel) && voxel > 0.0);
  Require(config.synthetic.has_value() || (config.lower.has_value() && config.upper.has_value()));
  const Eigen::Isometry3d X_LU = occlude::app::StartPoseOf(config, Eigen::Vector3d::Zero());
  Require(X_LU.matrix().allFinite());
  Require(occlude::app::RigidTransformError(X_LU.matrix()).empty());
  return 0;
}
