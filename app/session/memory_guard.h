// The commands' memory guard: before anything is voxelized, the estimated peak
// memory of what a command is about to build (collision/memory_estimate.h) is
// compared with the budget, and a run that would not fit stops with one line
// that names the smallest voxel size that fits, instead of swapping or being
// killed by the kernel halfway through.
//
// The budget: `--memory-budget-mb` when given, else the case config's
// `limits.memory_budget_mb`, else a quarter of the physical memory (or of the
// container's limit). Every command that builds trees or an oracle adds the
// option (cli/options.h: AddMemoryBudgetOption) and calls CheckMemory before building.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "occlude/collision/memory_estimate.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

struct MemoryBudget {
  std::size_t bytes = 0;
  std::string source;  ///< where it came from, for messages ("--memory-budget-mb", ...)
};

/// The budget in force: the option (> 0), else the config's value, else the default.
MemoryBudget ResolveMemoryBudget(double option_mb, std::optional<double> config_mb = std::nullopt);

/// A mesh the command voxelizes: its name in messages and its largest extent.
struct MeshExtent {
  std::string name;
  double extent_mm = 0.0;
};
/// The files of a jaw for messages: "a.stl", or "a.stl + 2 more part files".
std::string JawFilesName(const std::vector<std::string>& files);
/// {name, largest extent of `mesh`}.
MeshExtent ExtentOf(const std::string& name, const io::TriangleMesh& mesh);

/// What a command builds and how the user changes its voxel size.
struct MemoryCheck {
  std::string subject;        ///< starts the message: the files or config concerned
  std::string building;       ///< "the sphere trees", "the contact oracle and the map fields"
  std::string voxel_fix;      ///< how to set a voxel size: "--voxel", "accuracy.voxel_mm"
  double max_voxel_mm = 5.0;  ///< largest voxel size the command accepts
  /// What to do when no voxel size fits (what else the memory grows with).
  std::string no_fit_fix = "decimate the meshes";
  /// The meshes, for the grid-size check (a grid has at most 2^21 voxels per axis).
  std::vector<MeshExtent> meshes = {};
};

/// Throws UserError when a mesh's voxel grid would have too many voxels along
/// an axis at `voxel_mm` ("<mesh>: the mesh spans ... mm: ... the smallest voxel
/// size that fits is about ..."), or when `peak(voxel_mm)` exceeds the budget:
/// "<subject>: building <what> at voxel 0.05 mm needs about 3100 MB, over the
/// memory budget of 2000 MB (<source>); the smallest voxel size that fits is
/// about 0.081 mm: set <voxel_fix> to at least that, or raise the budget with
/// --memory-budget-mb or limits.memory_budget_mb".
void CheckMemory(const MemoryCheck& check,
                 const std::function<collision::MemoryEstimate(double voxel_mm)>& estimate,
                 double voxel_mm, const MemoryBudget& budget);

/// The estimate of both jaws' sphere trees built with `options` (at the voxel
/// size passed), for CheckMemory. The meshes must outlive the function.
std::function<collision::MemoryEstimate(double voxel_mm)> SphereTreePairEstimate(
    const io::TriangleMesh& lower, const io::TriangleMesh& upper,
    const collision::SphereTreeOptions& options);

/// Megabytes (10^6 bytes) as text with at most 3 significant digits above 10.
std::string Megabytes(std::size_t bytes);

}  // namespace occlude::app
