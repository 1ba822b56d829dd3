// The Implicit Sphere Tree of one mesh: its sparse voxel grid, the octree over
// the surface voxels, and (optionally) the explicit "saved IST" the paper
// proposes: every node's sphere precomputed into flat structure-of-arrays
// storage, so queries only traverse.
//
// Frame: everything is in the mesh's own frame F, mm. Build once per mesh and
// voxel size; queries between two trees take the pose of one in the other.
#pragma once

#include <memory>
#include <vector>

#include "occlude/collision/distance_bound.h"
#include "occlude/collision/octree.h"
#include "occlude/collision/voxel_grid.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::collision {

/// How a node's bounding sphere is obtained during a query.
enum class SphereMode {
  kSimple,     ///< implicit: encloses the node's cube (sqrt(3)/2 * edge), derived on the fly
  kOptimized,  ///< implicit: smallest sphere of the occupied child cubes, from the lookup table
  kExplicit,   ///< precomputed at build time (from `SphereTreeOptions::explicit_from`)
};
const char* ToString(SphereMode mode);

struct SphereTreeOptions {
  VoxelizeOptions voxelize;                           ///< voxel size and classification
  bool build_explicit = true;                         ///< precompute the saved IST
  SphereMode explicit_from = SphereMode::kOptimized;  ///< kSimple or kOptimized
  /// Build the DistanceBound of the surface voxels (lets queries prune a node
  /// of the other tree that is far from this whole tree in O(1)).
  bool build_distance_bound = true;
  /// Threads of the build (0 = every core); the tree is the same for any count. 1 by default:
  /// the paper's figures time single-threaded builds.
  int threads = 1;
};

/// Per-level figures of the paper (Figs. 7-9).
struct LevelStats {
  int level = 0;
  std::size_t nodes = 0;
  double simple_volume_mm3 = 0.0;     ///< total volume of the simple spheres
  double optimized_volume_mm3 = 0.0;  ///< total volume of the optimized spheres
};

struct SphereTreeStats {
  VoxelizeStats voxelize;
  std::vector<LevelStats> levels;  ///< index = level (0 = leaves)
  std::size_t nodes = 0;
  std::size_t leaves = 0;
  double seconds_voxelize = 0.0;
  double seconds_octree = 0.0;
  double seconds_explicit = 0.0;
  double seconds_bound = 0.0;
  std::size_t bytes_grid = 0;
  std::size_t bytes_octree = 0;
  std::size_t bytes_explicit = 0;
  std::size_t bytes_mesh = 0;
  std::size_t bytes_bound = 0;
  std::size_t total_bytes() const {
    return bytes_grid + bytes_octree + bytes_explicit + bytes_mesh + bytes_bound;
  }
  double total_seconds() const {
    return seconds_voxelize + seconds_octree + seconds_explicit + seconds_bound;
  }
};

/// Explicit spheres, one 64-byte record per octree node (frame F, mm). The
/// records are an array of structures on purpose: the descent visits nodes in
/// an order no prefetcher predicts, and one cache line per node visit measured
/// about 5x faster than nine structure-of-arrays streams.
///
/// Besides the sphere, each node stores a slab: a unit normal n (the
/// area-weighted mean of its triangles' normals) and the range [lo, hi] of
/// (x - centre) . n over every voxel cube x beneath it. The node's voxels lie in
/// sphere AND slab, and the slab is thin where the surface is flat, which is
/// where spheres are weakest (two occlusal surfaces facing each other). Nodes
/// whose normals cancel get lo = -radius, hi = radius (the slab then adds
/// nothing). Normals are float; lo and hi are rounded outward, so the slab is
/// conservative.
struct alignas(64) ExplicitNode {
  double cx = 0.0, cy = 0.0, cz = 0.0;  ///< sphere centre, F
  double radius = 0.0;
  float nx = 0.0f, ny = 0.0f, nz = 1.0f;  ///< slab normal (unit), F
  float slab_lo = 0.0f, slab_hi = 0.0f;   ///< slab range about the centre
};
struct ExplicitSpheres {
  SphereMode from = SphereMode::kOptimized;
  std::vector<ExplicitNode> nodes;
  /// The same spheres as four floats per node (centre, radius), the radius
  /// grown to cover the float rounding of the centre: for the descents that
  /// read only spheres (a quarter of the memory traffic of `nodes`).
  std::vector<Eigen::Vector4f> compact;
  bool empty() const { return nodes.empty(); }
  std::size_t MemoryBytes() const {
    return nodes.capacity() * sizeof(ExplicitNode) + compact.capacity() * sizeof(Eigen::Vector4f);
  }
};

class SphereTree {
 public:
  /// Voxelizes `mesh_F` and builds the octree (and explicit spheres). Throws
  /// VoxelizeError for unusable sizes or budgets. The mesh is kept (shared) for
  /// the exact triangle-level refinement.
  static SphereTree Build(std::shared_ptr<const io::TriangleMesh> mesh_F,
                          const SphereTreeOptions& options = {});

  const io::TriangleMesh& mesh() const { return *mesh_; }
  const VoxelGrid& grid() const { return grid_; }
  const Octree& octree() const { return octree_; }
  const ExplicitSpheres& explicit_spheres() const { return explicit_; }
  /// Lower bound of the distance to this tree's voxels (empty when not built).
  const DistanceBound& distance_bound() const { return bound_; }
  const SphereTreeStats& stats() const { return stats_; }
  double voxel_size_mm() const { return grid_.voxel_size_mm; }
  bool empty() const { return octree_.empty(); }

  /// Edge of a node at `level`, mm.
  double edge(int level) const { return std::ldexp(grid_.voxel_size_mm, level); }
  /// Centre of node n's cube in F, mm.
  Eigen::Vector3d CubeCenter(std::size_t node, int level) const;
  /// The sphere of node n for an implicit mode (kSimple or kOptimized), in F.
  void ImplicitSphere(std::size_t node, int level, SphereMode mode, Eigen::Vector3d* center,
                      double* radius) const;

 private:
  friend struct detail::OracleCodec;
  std::shared_ptr<const io::TriangleMesh> mesh_;
  VoxelGrid grid_;
  Octree octree_;
  ExplicitSpheres explicit_;
  DistanceBound bound_;
  SphereTreeStats stats_;
};

}  // namespace occlude::collision
