// Inputs of the `occlude bench` modes (see bench_inputs.h).
#include "bench/bench_inputs.h"

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "base/user_error.h"
#include "occlude/angles.h"
#include "occlude/collision/oracle.h"
#include "session/jaw_pair.h"

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
    if (std::abs(a[i]) > std::cos(RadiansFromDegrees(30.0))) {
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

BenchCase LoadBenchCase(const std::string& case_dir, std::size_t synthetic, std::uint32_t seed,
                        const std::string& axis) {
  if (!case_dir.empty()) {
    BenchCase bc{LoadCaseFolder(case_dir, "--case needs a folder with upper.stl and lower.stl")};
    bc.axis_L = BenchAxis(axis, *bc.lower_L, *bc.upper_U);  // given in L at the bite: U = L
    return bc;
  }
  BenchCase bc{SyntheticJawPair(synthetic, seed)};
  bc.axis_L = axis == "auto" ? *bc.occlusal_axis_L
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
