// Sparse voxelization of a triangle mesh (the paper's "spatial hashing", but
// with time and memory proportional to the surface, not to the bounding cube).
//
// Frame and units: the grid lives in the mesh's own frame F, in mm. Voxel
// (i, j, k) is the closed cube [origin_F + s*(i,j,k), origin_F + s*(i+1,j+1,k+1)]
// with s = voxel_size_mm; i, j, k are in [0, dims) and dims may be any size
// (not only powers of two). Voxels are keyed by Morton code (morton.h).
//
// Classes (after the paper, from McNeely et al.):
//   Surface   - a triangle overlaps the voxel cube (exact separating-axis test,
//               touching counts; the cube is the one of VoxelCenter and
//               SurfaceHalfSize, grown by kSurfaceSlack so that no triangle can
//               slip through a floating-point seam between neighbouring cubes);
//   Proximity - not Surface, and within about `proximity_layers` voxels of a
//               surface voxel on the outward side of its triangles' normals;
//   Interior  - not Surface, centre inside a closed (edge-manifold, watertight)
//               connected component of the mesh; never set for open parts.
//               Components are joined across edges, so closed shells that touch
//               an open part (teeth on the gingiva) stay closed. Interior wins
//               over Proximity: the classes are disjoint;
//   Undefined - everything else (not stored).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::collision {

/// Relative growth of the voxel cube in the Surface test. Neighbouring cubes
/// computed as centre +- s/2 in double can leave seams of a few ulps (a face
/// lying exactly on a voxel boundary could touch neither); this closes them for
/// coordinates up to about 10^6 voxel sizes from the frame's origin.
inline constexpr double kSurfaceSlack = 1e-9;

enum class VoxelClass : std::uint8_t {
  kUndefined = 0,
  kSurface = 1,
  kProximity = 2,
  kInterior = 3
};

struct VoxelizeOptions {
  double voxel_size_mm = 0.2;      ///< edge s of a voxel, mm; > 0
  bool classify_proximity = true;  ///< compute Proximity voxels
  int proximity_layers = 2;        ///< outward reach of Proximity, in voxels (paper: ~2s)
  bool classify_interior = true;   ///< compute Interior runs for closed components
  std::size_t memory_budget_bytes =
      0;  ///< 0 = unchecked; else VoxelizeError if the estimate exceeds it
};

/// A run of Interior voxels along x: voxels (x, y, z) for x in [x_begin, x_end).
struct VoxelRun {
  std::int32_t y = 0;
  std::int32_t z = 0;
  std::int32_t x_begin = 0;
  std::int32_t x_end = 0;
};

/// Counts and timings of one voxelization (for the paper's figures).
struct VoxelizeStats {
  std::size_t surface_voxels = 0;
  std::size_t proximity_voxels = 0;
  std::size_t interior_voxels = 0;       ///< sum of run lengths
  std::size_t triangle_voxel_tests = 0;  ///< exact triangle-cube tests performed
  std::size_t closed_components = 0;
  std::size_t open_components = 0;
  std::size_t interior_odd_rows = 0;  ///< (row, component) pairs skipped: odd crossings
  double seconds_surface = 0.0;
  double seconds_proximity = 0.0;
  double seconds_interior = 0.0;
};

struct VoxelGrid {
  double voxel_size_mm = 0.0;
  Eigen::Vector3d origin_F = Eigen::Vector3d::Zero();  ///< min corner of voxel (0,0,0), mm
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();      ///< voxels per axis (all coords < dims)

  std::vector<std::uint64_t> surface_keys;      ///< Morton codes, strictly increasing
  std::vector<std::uint32_t> triangle_offsets;  ///< CSR: size surface_keys.size() + 1
  std::vector<std::uint32_t> triangle_indices;  ///< triangles touching each surface voxel
  std::vector<std::uint64_t> proximity_keys;    ///< strictly increasing, disjoint from the others
  std::vector<VoxelRun> interior_runs;  ///< sorted by (z, y, x_begin); disjoint from surface

  std::size_t num_surface() const { return surface_keys.size(); }
  /// Triangles of surface voxel v (index into surface_keys): [begin, end) into triangle_indices.
  std::uint32_t triangles_begin(std::size_t v) const { return triangle_offsets[v]; }
  std::uint32_t triangles_end(std::size_t v) const { return triangle_offsets[v + 1]; }

  /// Centre of voxel (i, j, k) in F, mm.
  Eigen::Vector3d VoxelCenter(const Eigen::Vector3i& ijk) const {
    return origin_F + voxel_size_mm * (ijk.cast<double>() + Eigen::Vector3d::Constant(0.5));
  }
  /// Half edge of the cube that the Surface test uses around VoxelCenter.
  double SurfaceHalfSize() const { return 0.5 * voxel_size_mm * (1.0 + kSurfaceSlack); }
  /// Voxel containing point p_F (may be outside [0, dims)).
  Eigen::Vector3i VoxelOf(const Eigen::Vector3d& p_F) const;
  /// Class of a voxel (any coordinates; outside the grid is Undefined). O(log n).
  VoxelClass Classify(const Eigen::Vector3i& ijk) const;
  /// Classify(ijk) == kInterior, with one search instead of three (the classes are disjoint).
  bool IsInterior(const Eigen::Vector3i& ijk) const;
  /// Bytes held by the arrays above.
  std::size_t MemoryBytes() const;
};

/// Thrown for inputs that cannot be voxelized (non-positive size, grid overflow,
/// memory budget exceeded); the message says what to change.
class VoxelizeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Voxelizes `mesh` (frame F, mm). Cost grows with the number of surface voxels
/// and triangles, never with the bounding volume. Deterministic.
VoxelGrid Voxelize(const io::TriangleMesh& mesh, const VoxelizeOptions& options,
                   VoxelizeStats* stats = nullptr);

/// Estimate of the bytes Voxelize will need (from surface area and voxel size),
/// used for the memory guard before any allocation.
std::size_t EstimateVoxelizeBytes(const io::TriangleMesh& mesh, const VoxelizeOptions& options);

}  // namespace occlude::collision
