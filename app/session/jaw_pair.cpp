// Jaw pairs and their loader (see jaw_pair.h).
#include "session/jaw_pair.h"

#include <iostream>

#include "base/tasks.h"
#include "base/user_error.h"
#include "session/synthetic_case.h"

namespace occlude::app {
namespace {

void PrintWarnings(const io::LoadReport& report) {
  for (const auto& w : report.warnings) std::cerr << "occlude: warning: " << w << "\n";
}

std::shared_ptr<const io::TriangleMesh> LoadJawQuietly(
    const std::vector<std::filesystem::path>& files, bool parts, io::LengthUnit unit,
    io::LoadReport* report) {
  io::LoadOptions options;
  options.unit = unit;
  try {
    return std::make_shared<io::TriangleMesh>(parts ? io::LoadJawParts(files, options, report)
                                                    : io::LoadMesh(files.front(), options, report));
  } catch (const io::MeshError& e) {
    throw UserError(e.what());
  }
}

void CheckExists(const std::filesystem::path& file, const std::string& missing_hint) {
  if (!std::filesystem::exists(file)) {
    throw UserError(file.string() + ": not found (" + missing_hint + ")");
  }
}

struct JawFilesToLoad {
  std::vector<std::filesystem::path> files;
  bool parts = false;
  io::LengthUnit unit = io::LengthUnit::kMillimetre;
};

// Both jaws read at once (the parsing and welding of one scan take ~0.05 s); the warnings
// printed in order, lower first, and the lower's error thrown first, as when read one by one.
void LoadBothJaws(const JawFilesToLoad& lower, const JawFilesToLoad& upper, JawPair* pair) {
  io::LoadReport lower_report, upper_report;
  RunTasks(
      {[&] { pair->lower_L = LoadJawQuietly(lower.files, lower.parts, lower.unit, &lower_report); },
       [&] {
         pair->upper_U = LoadJawQuietly(upper.files, upper.parts, upper.unit, &upper_report);
       }});
  PrintWarnings(lower_report);
  PrintWarnings(upper_report);
}

std::string FolderName(const std::filesystem::path& dir) {
  return dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
}

}  // namespace

std::shared_ptr<const io::TriangleMesh> LoadJaw(const std::vector<std::filesystem::path>& files,
                                                bool parts, io::LengthUnit unit) {
  io::LoadReport report;
  auto mesh = LoadJawQuietly(files, parts, unit, &report);
  PrintWarnings(report);
  return mesh;
}

std::shared_ptr<const io::TriangleMesh> LoadExistingMesh(const std::filesystem::path& file,
                                                         const std::string& missing_hint) {
  CheckExists(file, missing_hint);
  return LoadJaw({file}, false);
}

JawPair LoadCaseFolder(const std::filesystem::path& dir, const std::string& missing_hint) {
  if (!std::filesystem::is_directory(dir)) {
    throw UserError("--case: '" + dir.string() +
                    "' is not a folder (it must hold upper.stl and lower.stl)");
  }
  JawPair pair;
  pair.name = FolderName(dir);
  CheckExists(dir / "lower.stl", missing_hint);
  CheckExists(dir / "upper.stl", missing_hint);
  LoadBothJaws({{dir / "lower.stl"}}, {{dir / "upper.stl"}}, &pair);  // in L at the bite: U = L
  return pair;
}

JawPair SyntheticJawPair(std::size_t triangles, std::uint32_t seed) {
  io::SyntheticJawOptions options;
  options.triangles_per_jaw = triangles;
  options.seed = seed;
  const io::SyntheticJawPair jaws = MakeSyntheticOrExplain(options);
  JawPair pair;
  pair.name = "synthetic-" + std::to_string(triangles);
  pair.lower_L = std::make_shared<io::TriangleMesh>(jaws.lower_L);
  pair.upper_U = std::make_shared<io::TriangleMesh>(jaws.upper_U);
  pair.X_LU_ref = jaws.X_LU;
  pair.occlusal_axis_L = jaws.occlusal_axis_L;
  for (const auto& c : jaws.contacts) pair.truth_contacts_L.push_back(c.p_L);
  return pair;
}

JawPair LoadConfigJaws(const CaseConfig& config) {
  if (config.synthetic)
    return SyntheticJawPair(config.synthetic->triangles, config.synthetic->seed);
  JawPair pair;
  pair.name = config.name;
  LoadBothJaws({config.lower->files, config.lower->parts, config.units},
               {config.upper->files, config.upper->parts, config.units}, &pair);
  return pair;
}

JawPair AtReference(JawPair pair) {
  if (pair.X_LU_ref.matrix() == Eigen::Matrix4d::Identity()) return pair;
  pair.upper_U = std::make_shared<io::TriangleMesh>(pair.upper_U->Transformed(pair.X_LU_ref));
  pair.X_LU_ref = Eigen::Isometry3d::Identity();
  return pair;
}

}  // namespace occlude::app
