// Case folders (see case_folder.h).
#include "session/jaw_pair.h"

#include <iostream>

#include "base/user_error.h"
#include "occlude/io/mesh_io.h"
#include "session/synthetic_case.h"

namespace occlude::app {
namespace {

std::shared_ptr<const io::TriangleMesh> LoadJaw(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) {
    throw UserError(file.string() + ": not found (a case folder holds upper.stl and lower.stl)");
  }
  try {
    io::LoadReport report;
    auto mesh = std::make_shared<io::TriangleMesh>(io::LoadMesh(file, {}, &report));
    for (const auto& w : report.warnings) std::cerr << "occlude: warning: " << w << "\n";
    return mesh;
  } catch (const io::MeshError& e) {
    throw UserError(e.what());
  }
}

}  // namespace

JawPairCase LoadCaseFolder(const std::filesystem::path& dir) {
  if (!std::filesystem::is_directory(dir)) {
    throw UserError("--case: '" + dir.string() +
                    "' is not a folder (it must hold upper.stl and lower.stl)");
  }
  JawPairCase c;
  c.name = dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
  c.lower_L = LoadJaw(dir / "lower.stl");
  c.upper_U = LoadJaw(dir / "upper.stl");
  return c;
}

JawPairCase SyntheticJawPairCase(std::size_t triangles, std::uint32_t seed) {
  io::SyntheticJawOptions options;
  options.triangles_per_jaw = triangles;
  options.seed = seed;
  const io::SyntheticJawPair jaws = MakeSyntheticOrExplain(options);
  JawPairCase c;
  c.name = "synthetic-" + std::to_string(triangles);
  c.lower_L = std::make_shared<io::TriangleMesh>(jaws.lower_L);
  c.upper_U = std::make_shared<io::TriangleMesh>(jaws.upper_U);
  c.X_LU_ref = jaws.X_LU;
  return c;
}

}  // namespace occlude::app
