// Jaw pairs and the one loader of jaw meshes: one jaw from a mesh file or from part files, a
// case folder (DIR/lower.stl and DIR/upper.stl in one frame at the registered bite), the meshes
// a case config names, and the built-in synthetic pair. Every command and measuring tool loads
// its jaws here.
//
// Frames: the lower jaw is in its frame L, the upper in its own frame U (the frame its file came
// in), and X_LU_ref is the reference pose of U in L: the registered bite (identity for files
// exported in one frame) or the synthetic pair's designed bite. Errors are UserErrors naming the
// file or folder; mesh warnings go to stderr as "occlude: warning: ..." lines.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "config/case_config.h"
#include "occlude/io/mesh_io.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// A jaw pair and its reference pose.
struct JawPair {
  std::string name;  ///< the case folder's name, or "synthetic-<triangles>"
  std::shared_ptr<const io::TriangleMesh> lower_L, upper_U;
  Eigen::Isometry3d X_LU_ref = Eigen::Isometry3d::Identity();
  /// Synthetic pair only: the designed occlusal axis (unit, lower -> upper, in L) and the
  /// known contact points (in L, the upper at X_LU_ref).
  std::optional<Eigen::Vector3d> occlusal_axis_L;
  std::vector<Eigen::Vector3d> truth_contacts_L;
};

/// One jaw: a single mesh file, or (`parts`) part files merged with tooth numbers read from
/// names like Tooth_14 (io::LoadJawParts), converted from `unit` to millimetres.
std::shared_ptr<const io::TriangleMesh> LoadJaw(const std::vector<std::filesystem::path>& files,
                                                bool parts,
                                                io::LengthUnit unit = io::LengthUnit::kMillimetre);

/// A mesh file in millimetres that must exist: "<file>: not found (<missing_hint>)" when not.
std::shared_ptr<const io::TriangleMesh> LoadExistingMesh(const std::filesystem::path& file,
                                                         const std::string& missing_hint);

/// What a missing file of a case folder is told by default.
inline constexpr const char* kCaseFolderHint = "a case folder holds upper.stl and lower.stl";

/// DIR/lower.stl and DIR/upper.stl at X_LU_ref = identity, named after the folder. Not a
/// folder: "--case: '<dir>' is not a folder (it must hold upper.stl and lower.stl)"; a missing
/// file: "<file>: not found (<missing_hint>)".
JawPair LoadCaseFolder(const std::filesystem::path& dir,
                       const std::string& missing_hint = kCaseFolderHint);

/// The synthetic pair with `triangles` per jaw (seed), the upper in U at its designed bite,
/// named "synthetic-<triangles>". A triangle budget out of range names --triangles.
JawPair SyntheticJawPair(std::size_t triangles, std::uint32_t seed);

/// The meshes a case config names: [lower] and [upper] files or part files in the config's
/// units (X_LU_ref = identity), or the [synthetic] pair.
JawPair LoadConfigJaws(const CaseConfig& config);

/// The pair with the upper jaw re-expressed in L at its reference pose (upper_U becomes
/// X_LU_ref * upper_U and X_LU_ref the identity), so that X_LU = identity is the reference:
/// the frame of a case session. A pair already at identity is returned as it is.
JawPair AtReference(JawPair pair);

}  // namespace occlude::app
