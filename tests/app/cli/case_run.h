// What the tests of `propose`, `refine` and `demo` share: the smallest synthetic case (known
// bite at X_LU = identity) started a little off the bite, and readers of what they write.
#pragma once

#include <Eigen/Geometry>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace occlude::app {

using nlohmann::json;

// Within the success bar of `occlude validate` (0.3 mm) of the designed bite.
inline constexpr double kFoundMm = 0.3;

inline std::string Config(const std::filesystem::path& out,
                          const std::string& adjust = "[0.0, 0.0, 0.0]",
                          const std::string& extra = "") {
  return "[synthetic]\ntriangles = 5000\n[accuracy]\nvoxel_mm = 0.5\n[solver]\nstarts = "
         "3\nproposals = 2\n" +
         extra +
         "[start]\ntranslation_mm = [0.4, 0.5, -0.3]\nrotation_deg = [0.5, -0.8, 0.4]\n"
         "[adjust]\ntranslation_mm = " +
         adjust + "\n[output]\nfolder = \"" + out.string() + "\"\n";
}

inline void Write(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file) << text;
}

inline json ReadJson(const std::filesystem::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

inline double TranslationNorm(const Eigen::Isometry3d& X) { return X.translation().norm(); }

}  // namespace occlude::app
