// Case folders as the measuring commands (validate, and later bench) take them:
// `DIR/upper.stl` and `DIR/lower.stl` in one frame at the registered bite, or
// the generated synthetic pair. (The machine line stated with every figure: MachineLine,
// bench_inputs.h.)
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <string>

#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// A jaw pair with its reference pose: lower in L, upper in its own frame U, X_LU_ref the
/// registered (or designed) bite. Case folders give both meshes in L, so X_LU_ref = identity.
struct JawPairCase {
  std::string name;
  std::shared_ptr<const io::TriangleMesh> lower_L, upper_U;
  Eigen::Isometry3d X_LU_ref = Eigen::Isometry3d::Identity();
};

/// Loads DIR/lower.stl and DIR/upper.stl. Throws UserError naming the folder or file.
JawPairCase LoadCaseFolder(const std::filesystem::path& dir);
/// The synthetic pair with `triangles` per jaw (seed), upper in U at its designed bite.
JawPairCase SyntheticJawPairCase(std::size_t triangles, std::uint32_t seed);

}  // namespace occlude::app
