// Case configuration files (TOML): which jaw meshes, how accurately, which
// contact thresholds, how the planner searches, where it starts and what it may
// move, and where the outputs go. `LoadCaseConfig` validates everything at the
// boundary: every error is one line naming the file, the key (with its table
// path, e.g. `contact.band_mm`) and the fix; unknown keys suggest the closest
// valid key. The keys, their units and defaults (see examples/*.toml):
//
//   [case]      name = "..."; units = "mm" (mm, cm, m, um, in);
//               up_axis = "auto" or "+y", "-z", ... (occlusal axis lower -> upper, in L)
//   [lower], [upper]  file = "lower.stl"  or  parts = ["teeth/Tooth_18.stl", ...]
//               (tooth numbers from names like Tooth_18; 0 = gingiva/base)
//   [synthetic] triangles = 20000; seed = 1  (the built-in pair instead of [lower]/[upper])
//   [accuracy]  accuracy_mm = 0.02 (wanted contact-distance accuracy: picks the voxel size
//               and oracle level from a measured table, resolution_choice.h);
//               table = "accuracy-table.json" (of `occlude bench --accuracy`; default: the
//               one measured on a-bite-3shape, built in); voxel_mm (explicit voxel size,
//               overrides accuracy_mm); sample_spacing_mm = 0.3;
//               region_of_interest = true (model only what the search can reach)
//   [contact]   band_mm = 0.1 in (0, 5]; max_penetration_mm = 0.05 in [0, 5]
//   [solver]    name = "auto"; starts = 16; seed = 1; threads = 0 (all cores);
//               proposals = 3 (K); max_seconds = 60; scope = "local" (from the start pose)
//               or "global" (no start pose: every intercuspation of the two arches, ranked by
//               [clinical]); [solver.options] free table; [solver.global] sagittal_step_mm = 1,
//               max_basins = 12, max_refined = 6 (the global search's scan)
//   [clinical]  molar_class, canine_class (or _right / _left) = "I" | "II" | "III";
//               overjet_mm, overbite_mm = [min, max]; midline_max_mm; mode = "rank" |
//               "constraint" (config/clinical_targets.h; the default ranking without it)
//   [bounds]    tx_mm, ty_mm, tz_mm = [min, max]; rx_deg, ry_deg, rz_deg = [min, max]
//               (about the start pose); locked = ["rz", ...] (never all six)
//   [start]     translation_mm = [x, y, z]; rotation_deg = [x, y, z] (rotation vector about
//               the pivot)  or  matrix = 4x4 rigid X_LU;  pivot_mm = [x, y, z] (default: centre
//               of the upper arch's occlusal surface)
//   [adjust]    translation_mm, rotation_deg: deltas applied by `refine`
//   [refine]    hold = "adjusted" (default: the degrees of freedom [adjust] changes stay at
//               the adjusted value while the others settle), "none", or ["tx", "rz", ...]
//   [output]    folder = "out/case" (relative to the config file)
//   [report]    map_max_mm = 0.5 (colour scale); map_penetration_from_mm = 0.01;
//               image_width_px = 1000
//   [limits]    memory_budget_mb (what the trees and fields may take; default a quarter
//               of the physical memory; --memory-budget-mb overrides); cache_mb = 2048
//               (the oracle cache's size, session/oracle_cache.h)
//   [landmarks] file = "landmarks.csv" (given landmarks overriding detected ones, the format
//               of occlude/io/landmark_file.h; --landmarks overrides)
//
// Poses: X_LU is the pose of the upper mesh as given (frame U) in the lower's frame L;
// translation/rotation parameters follow planner::ComposePose about the pivot with the
// reference pose = identity (the jaws as given).
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "config/clinical_targets.h"
#include "config/resolution_choice.h"
#include "occlude/io/mesh_io.h"
#include "occlude/planner/pose.h"

namespace occlude::app {

/// The six degrees of freedom of the upper jaw, in config order.
enum class Dof { kTx = 0, kTy, kTz, kRx, kRy, kRz };
inline constexpr int kNumDofs = 6;
/// "tx", "ty", "tz", "rx", "ry", "rz".
const char* DofName(int dof);

/// One jaw's mesh files: a single file, or part files (one per tooth + gingiva).
struct JawFiles {
  std::vector<std::filesystem::path> files;  ///< absolute paths, checked to exist
  bool parts = false;                        ///< from `parts = [...]`
};

/// The built-in synthetic pair (io::MakeSyntheticJawPair) as the case's meshes.
struct SyntheticSource {
  std::size_t triangles = 20000;
  std::uint32_t seed = 1;
};

struct DofRange {
  double min = 0.0;
  double max = 0.0;
};

struct SolverSettings {
  using Value = std::variant<bool, std::int64_t, double, std::string>;
  std::string name = "auto";
  int starts = 16;              ///< random starts
  std::uint64_t seed = 1;       ///< random seed of the starts
  int threads = 0;              ///< 0 = all cores
  int proposals = 3;            ///< K poses `propose` keeps
  double max_seconds = 60;      ///< wall-clock budget of a search
  std::string scope = "local";  ///< "local" (from the start pose) or "global"
  /// [solver.global]: the global search's scan (planner::GlobalScanSettings; unset = its
  /// defaults): sagittal_step_mm, max_basins, max_refined.
  std::optional<double> global_sagittal_step_mm;
  std::optional<int> global_max_basins, global_max_refined;
  std::map<std::string, Value> options;  ///< [solver.options], passed to the solver as is
};

struct StartPose {
  std::optional<Eigen::Matrix4d> matrix;  ///< absolute X_LU (rigid, finite) when given
  planner::PoseParameters params;         ///< used when no matrix
  std::optional<Eigen::Vector3d> pivot_mm;
};

struct ReportSettings {
  double map_max_mm = 0.5;                ///< colour scale 0..this; farther = neutral
  double map_penetration_from_mm = 0.01;  ///< depth shown in the penetration colour
  int image_width_px = 1000;
};

/// [refine]: what `refine` keeps at the adjusted pose while the other degrees of freedom
/// settle (on top of bounds.locked).
struct RefineSettings {
  bool hold_adjusted = true;          ///< hold = "adjusted": those [adjust] changes (non-zero)
  std::array<bool, kNumDofs> hold{};  ///< else these (all false for "none")
};

struct CaseConfig {
  std::filesystem::path file;  ///< the config file (absolute)
  std::string name;            ///< default: the file stem
  io::LengthUnit units = io::LengthUnit::kMillimetre;
  std::optional<Eigen::Vector3d> up_axis_L;  ///< unit; nullopt = estimate

  std::optional<JawFiles> lower, upper;  ///< both set, or `synthetic`
  std::optional<SyntheticSource> synthetic;

  double accuracy_mm = 0.02;
  std::optional<double> voxel_mm;
  std::optional<std::filesystem::path> accuracy_table;  ///< absolute when set
  /// The voxel size and oracle level in use and why (from voxel_mm, or accuracy_mm and the
  /// table); set by the parser.
  ResolutionChoice resolution = ChooseResolution(0.02, DefaultResolutionTable());
  double sample_spacing_mm = 0.3;
  /// [accuracy] region_of_interest: the search's oracles model only the triangles of each jaw
  /// that can come within reach of the other over the bounds (collision/region_of_interest.h).
  bool region_of_interest = true;

  double contact_band_mm = 0.1;
  double max_penetration_mm = 0.05;

  SolverSettings solver;
  ClinicalTargets clinical;  ///< [clinical], or the default ranking
  std::array<DofRange, kNumDofs> bounds{{{-3, 3}, {-3, 3}, {-3, 3}, {-5, 5}, {-5, 5}, {-5, 5}}};
  std::array<bool, kNumDofs> locked{};

  StartPose start;
  planner::PoseParameters adjust;
  RefineSettings refine;
  std::optional<std::filesystem::path> output_dir;  ///< absolute when set
  ReportSettings report;
  std::optional<double> memory_budget_mb;  ///< [limits]; nullopt = the default budget
  /// [landmarks] file (absolute, checked to exist), or a command's --landmarks.
  std::optional<std::filesystem::path> landmarks_file;
  double cache_mb = 2048;  ///< [limits] cache_mb
  /// The oracle cache (session/oracle_cache.h): off with --no-cache; the folder of --cache
  /// DIR, empty = the default folder. Set by the commands, not by the file.
  bool cache_enabled = true;
  std::filesystem::path cache_folder;

  /// The finest voxel size the oracle uses: voxel_mm, or chosen for accuracy_mm.
  double VoxelSizeMm() const;
  /// The oracle's level at that voxel size (sub-voxel for an explicit voxel_mm).
  collision::AccuracyLevel OracleLevel() const { return resolution.chosen.level; }
};

/// Reads and validates a case file. Throws UserError (one line: file, key,
/// what is wrong, the fix). Relative paths resolve against the file's folder.
CaseConfig LoadCaseConfig(const std::filesystem::path& file);

/// Same, from text (`file` names the source in messages and anchors relative paths).
CaseConfig ParseCaseConfig(const std::string& text, const std::filesystem::path& file);

/// The start pose X_LU, given the pivot to use when the config gives none.
Eigen::Isometry3d StartPoseOf(const CaseConfig& config, const Eigen::Vector3d& default_pivot_L);

/// Levenshtein distance (for "did you mean" suggestions).
std::size_t EditDistance(const std::string& a, const std::string& b);

}  // namespace occlude::app
