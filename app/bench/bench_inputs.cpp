// Inputs of the `occlude bench` modes (see bench_inputs.h).
#include "bench/bench_inputs.h"

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "base/user_error.h"
#include "occlude/collision/oracle.h"
#include "occlude/io/mesh_io.h"
#include "session/synthetic_case.h"

namespace occlude::app {
namespace {

std::string ReadFirstLine(const char* file, const std::string& prefix) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (prefix.empty() || line.rfind(prefix, 0) == 0) return line;
  }
  return "";
}

}  // namespace

Eigen::Vector3d BenchAxis(const std::string& text, const io::TriangleMesh& lower_L,
                          const io::TriangleMesh& upper_L) {
  if (text == "auto") {
    const Eigen::Vector3d a =
        collision::EstimateArchFrame(lower_L, upper_L).occlusal_L.normalized();
    Eigen::Index i = 0;
    a.cwiseAbs().maxCoeff(&i);
    if (std::abs(a[i]) > std::cos(30.0 * 3.14159265358979 / 180.0)) {
      return Eigen::Vector3d::Unit(i) * (a[i] > 0 ? 1.0 : -1.0);
    }
    return a;
  }
  const bool negative = !text.empty() && text[0] == '-';
  const std::string name = (negative || (!text.empty() && text[0] == '+')) ? text.substr(1) : text;
  if (name != "x" && name != "y" && name != "z") {
    throw UserError("--axis: '" + text + "' is not an axis (use auto, x, y, z, -x, -y or -z)");
  }
  const Eigen::Vector3d axis = Eigen::Vector3d::Unit(name[0] - 'x');
  return negative ? Eigen::Vector3d(-axis) : axis;
}

std::shared_ptr<const io::TriangleMesh> LoadBenchMesh(const std::filesystem::path& file,
                                                      const std::string& what) {
  if (!std::filesystem::exists(file)) throw UserError(file.string() + ": not found (" + what + ")");
  try {
    io::LoadReport report;
    auto mesh = std::make_shared<io::TriangleMesh>(io::LoadMesh(file, {}, &report));
    for (const auto& w : report.warnings) std::cerr << "occlude: warning: " << w << "\n";
    return mesh;
  } catch (const io::MeshError& e) {
    throw UserError(e.what());
  }
}

BenchCase LoadBenchCase(const std::string& case_dir, std::size_t synthetic, std::uint32_t seed,
                        const std::string& axis) {
  BenchCase bc;
  if (!case_dir.empty()) {
    const std::filesystem::path dir(case_dir);
    if (!std::filesystem::is_directory(dir)) {
      throw UserError("--case: '" + case_dir +
                      "' is not a folder (it must hold upper.stl and lower.stl)");
    }
    bc.name =
        dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
    const std::string what = "--case needs a folder with upper.stl and lower.stl";
    bc.lower_L = LoadBenchMesh(dir / "lower.stl", what);
    bc.upper_U = LoadBenchMesh(dir / "upper.stl", what);  // given in L at the bite: U = L
    bc.axis_L = BenchAxis(axis, *bc.lower_L, *bc.upper_U);
    return bc;
  }
  io::SyntheticJawOptions options;
  options.triangles_per_jaw = synthetic;
  options.seed = seed;
  const io::SyntheticJawPair jaws = MakeSyntheticOrExplain(options);
  bc.name = "synthetic-" + std::to_string(synthetic);
  bc.lower_L = std::make_shared<io::TriangleMesh>(jaws.lower_L);
  bc.upper_U = std::make_shared<io::TriangleMesh>(jaws.upper_U);
  bc.X_LU_ref = jaws.X_LU;
  bc.axis_L = axis == "auto" ? jaws.occlusal_axis_L
                             : BenchAxis(axis, *bc.lower_L, bc.upper_U->Transformed(bc.X_LU_ref));
  return bc;
}

std::string MachineLine() {
  std::string cpu = ReadFirstLine("/proc/cpuinfo", "model name");
  const auto colon = cpu.find(':');
  cpu = colon == std::string::npos ? std::string("unknown CPU") : cpu.substr(colon + 2);
  std::istringstream load(ReadFirstLine("/proc/loadavg", ""));
  std::string load1;
  load >> load1;
  return std::to_string(std::thread::hardware_concurrency()) + " cores (" + cpu + "), load " +
         (load1.empty() ? "?" : load1) + " at start";
}

}  // namespace occlude::app
