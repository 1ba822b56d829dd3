// Case folders and the machine line (see case_folder.h).
#include "case_folder.h"

#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "commands.h"
#include "occlude/io/mesh_io.h"
#include "synthetic_case.h"

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

std::string FirstLine(const char* file, const std::string& prefix) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (prefix.empty() || line.rfind(prefix, 0) == 0) return line;
  }
  return "";
}

}  // namespace

JawPairCase LoadCaseFolder(const std::filesystem::path& dir) {
  if (!std::filesystem::is_directory(dir)) {
    throw UserError("--case: '" + dir.string() + "' is not a folder (it must hold upper.stl and lower.stl)");
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

std::string MachineDescription() {
  std::string cpu = FirstLine("/proc/cpuinfo", "model name");
  const auto colon = cpu.find(':');
  cpu = colon == std::string::npos ? std::string("unknown CPU") : cpu.substr(colon + 2);
  std::istringstream load(FirstLine("/proc/loadavg", ""));
  std::string load1;
  load >> load1;
  return std::to_string(std::thread::hardware_concurrency()) + " cores (" + cpu + "), load " +
         (load1.empty() ? "?" : load1) + " at start";
}

}  // namespace occlude::app
