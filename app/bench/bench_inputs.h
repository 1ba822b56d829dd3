// Inputs shared by the `occlude bench` modes (the sweep, --haptic, --paper,
// --accuracy): a jaw pair from a case folder or the synthetic generator, a
// single mesh file, and the machine line stated with every figure.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "bench/bench.h"

namespace occlude::app {

/// "auto" (the lower-to-upper direction, snapped to a coordinate axis within
/// 30 degrees), or x, y, z with an optional sign. UserError otherwise.
Eigen::Vector3d BenchAxis(const std::string& text, const io::TriangleMesh& lower_L,
                          const io::TriangleMesh& upper_L);

/// The pair of `case_dir` (upper.stl and lower.stl in one frame at the bite) or,
/// when case_dir is empty, the synthetic pair of `synthetic` triangles per jaw.
BenchCase LoadBenchCase(const std::string& case_dir, std::size_t synthetic, std::uint32_t seed,
                        const std::string& axis);

/// Cores, CPU model and load average at the start.
std::string MachineLine();

}  // namespace occlude::app
