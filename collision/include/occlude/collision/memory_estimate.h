// How much memory the collision structures of a jaw pair will take, estimated
// before anything is built, so that a command can refuse a voxel size the
// machine cannot hold (and name one it can) instead of being killed halfway.
//
// The estimates read only the mesh (surface area A, triangle count T, vertex
// count V, and for the oracle the exact number of upper samples, O(T)) and the
// options. Every structure grows with the number of surface voxels, about
// 1.5 A / s^2 at voxel size s (a plane of unit normal n meets |n|_1 A / s^2
// voxels, 1.5 on average); the per-voxel and per-triangle byte counts below
// follow the storage of each structure, with the brick-based ones (distance
// bound, narrow band) fitted on the synthetic pair and the real jaws.
// `resident_bytes` is what the built object reports (SphereTree::stats()
// .total_bytes(), JawOracle::MemoryBytes(), NarrowBandSdf::MemoryBytes());
// tests/collision/memory_estimate_test.cpp holds it within a factor of 1.5 of
// those on real builds. `peak_bytes` adds the largest transient of the build
// (Voxelize's pair list and sort buffer, the oracle's raw samples) and is what
// a budget should be compared with.
#pragma once

#include <cstddef>
#include <functional>

#include "occlude/collision/oracle.h"
#include "occlude/collision/signed_distance.h"
#include "occlude/collision/sphere_tree.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::collision {

struct MemoryEstimate {
  std::size_t resident_bytes = 0;  ///< held by the structure once built
  std::size_t peak_bytes = 0;      ///< resident plus the largest transient while building

  MemoryEstimate& operator+=(const MemoryEstimate& other);
};

/// SphereTree::Build(mesh, options). The voxel size must be > 0 (else VoxelizeError).
MemoryEstimate EstimateSphereTreeMemory(const io::TriangleMesh& mesh,
                                        const SphereTreeOptions& options);

/// NarrowBandSdf::Build over a surface-only grid of `mesh` at `voxel_size_mm`
/// (as the report's map fields), plus that grid while building.
MemoryEstimate EstimateNarrowBandSdfMemory(const io::TriangleMesh& mesh, double voxel_size_mm,
                                           int dilation_voxels);

/// JawOracle(lower_L, upper_U, options): both trees, the lower's distance
/// field and the upper's samples.
MemoryEstimate EstimateOracleMemory(const io::TriangleMesh& lower_L,
                                    const io::TriangleMesh& upper_U, const OracleOptions& options);

/// Physical memory of the machine, or the cgroup's memory limit when that is
/// lower (containers); 0 when unknown.
std::size_t PhysicalMemoryBytes();

/// The default budget of the commands: a quarter of PhysicalMemoryBytes()
/// (1 GiB when that is unknown).
std::size_t DefaultMemoryBudgetBytes();

/// Smallest voxel size in [from_mm, max_mm] whose `peak_bytes(voxel)` fits
/// `budget_bytes`, to 0.5 %, found by bisection (the estimates decrease as the
/// voxel grows); +infinity when even max_mm does not fit.
double SmallestFittingVoxelMm(const std::function<std::size_t(double voxel_mm)>& peak_bytes,
                              double from_mm, double max_mm, std::size_t budget_bytes);

}  // namespace occlude::collision
