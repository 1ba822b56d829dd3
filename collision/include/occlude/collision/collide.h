// Queries between two Implicit Sphere Trees: simultaneous depth-first descent
// testing r_a + r_b >= |c_a - c_b| (paper eq. 4), then an exact test of the two
// voxel cubes at the leaves, then (optionally) exact triangle-level refinement.
//
// Frames: tree A's mesh is in frame A, tree B's in frame B, and X_AB is the pose
// of B in A. Every point in a result is expressed in A, in mm.
//
// What a leaf pair means: voxel a of A and voxel b of B form a pair when their
// cubes, each grown by delta/2 on every face, overlap (exact separating-axis
// test, touching counts). Every pair of voxel cubes within Euclidean distance
// delta is therefore reported (the test is conservative; it may also report
// pairs a little farther apart along a diagonal, never fewer). Internal nodes
// prune with spheres that enclose every voxel cube beneath them grown the same
// way, plus 1e-9 mm, so all sphere modes report exactly the same pairs; they
// differ only in the work done.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <vector>

#include "occlude/collision/sphere_tree.h"

namespace occlude::collision {

struct CollisionRequest {
  SphereMode spheres = SphereMode::kExplicit;  ///< sphere variant used by the descent
  double delta_mm = 0.0;                       ///< contact tolerance, mm (>= 0); 0 = overlap only
  bool first_only = false;         ///< boolean query: stop at the first pair (pairs has <= 1)
  std::size_t max_node_tests = 0;  ///< work budget in sphere-pair tests; 0 = unlimited
  bool exact = false;              ///< refine the voxel pairs to triangle pairs within delta
  /// Also prune a node whose sphere the other tree's DistanceBound proves
  /// farther than delta's reach from every voxel of that tree (an O(1) test of
  /// the node against the whole other tree, after the sphere test passed). The
  /// pairs reported are the same; only the work changes. Ignored for a tree
  /// built without its bound.
  bool distance_bound = true;
};

/// A reported leaf pair: indices of surface voxels in a.grid() and b.grid().
struct VoxelPair {
  std::uint32_t voxel_a = 0;
  std::uint32_t voxel_b = 0;
  bool operator==(const VoxelPair& o) const { return voxel_a == o.voxel_a && voxel_b == o.voxel_b; }
  bool operator<(const VoxelPair& o) const {
    return voxel_a != o.voxel_a ? voxel_a < o.voxel_a : voxel_b < o.voxel_b;
  }
};

/// An exact triangle pair within delta (frame A, mm).
struct TriangleContact {
  std::uint32_t triangle_a = 0;
  std::uint32_t triangle_b = 0;
  double distance_mm = 0.0;                            ///< Euclidean distance; 0 when intersecting
  Eigen::Vector3d p_A_on_a = Eigen::Vector3d::Zero();  ///< closest point on a, in A
  Eigen::Vector3d p_A_on_b = Eigen::Vector3d::Zero();  ///< closest point on b, in A
  bool intersecting = false;
};

struct CollisionResult {
  bool overlap = false;          ///< at least one leaf pair found
  bool complete = true;          ///< false when the work budget stopped the descent early
  std::size_t node_tests = 0;    ///< sphere-pair tests performed
  std::size_t leaf_tests = 0;    ///< exact voxel-cube tests performed
  std::size_t bound_tests = 0;   ///< distance-bound tests performed (request.distance_bound)
  std::vector<VoxelPair> pairs;  ///< in traversal order (not sorted)

  // Filled when request.exact:
  std::vector<TriangleContact> contacts;  ///< unique triangle pairs within delta, sorted by (a, b)
  bool triangles_intersect = false;       ///< some triangle pair intersects
  /// Smallest distance over the triangle pairs within delta; +inf when there is none
  /// (the meshes are then farther apart than delta, or the budget cut the search).
  double min_distance_mm = std::numeric_limits<double>::infinity();
  TriangleContact closest;         ///< the pair attaining min_distance_mm, if finite
  std::size_t triangle_tests = 0;  ///< unique triangle pairs examined

  void Clear();
};

/// Runs one query. Thread-safe: trees are only read; scratch memory is per thread.
/// Throws std::invalid_argument for a negative or non-finite delta or a
/// non-rigid X_AB.
void Collide(const SphereTree& a, const SphereTree& b, const Eigen::Isometry3d& X_AB,
             const CollisionRequest& request, CollisionResult* result);

/// A reusable pair for repeated queries with new poses (an optimizer's inner loop).
/// Holds references: both trees must outlive it.
class CollisionPair {
 public:
  CollisionPair(const SphereTree& a, const SphereTree& b) : a_(a), b_(b) {}
  void Query(const Eigen::Isometry3d& X_AB, const CollisionRequest& request,
             CollisionResult* result) const {
    Collide(a_, b_, X_AB, request, result);
  }
  /// Boolean query at voxel level with tolerance delta.
  bool Overlap(const Eigen::Isometry3d& X_AB, double delta_mm = 0.0,
               SphereMode mode = SphereMode::kExplicit) const;
  const SphereTree& a() const { return a_; }
  const SphereTree& b() const { return b_; }

 private:
  const SphereTree& a_;
  const SphereTree& b_;
};

/// One-sided query (the oracle's broad phase): the nodes ("cells") of B at
/// `cell_level` whose voxels come within reach of a voxel of A, by the same
/// conservative grown-cube test as the pair query (cell cube and voxel cube each
/// grown by reach_mm / 2). Each cell is reported once; every point of B's
/// surface within reach_mm of A's surface lies in a reported cell.
struct CellRequest {
  SphereMode spheres = SphereMode::kExplicit;
  double reach_mm = 0.3;  ///< mm, >= 0
  int cell_level = 1;     ///< 0 (voxels) .. 3
  /// A is descended down to this level: 0 = to its voxels, with the exact
  /// grown-cube test; above 0 a cell is reported as soon as its sphere (and slab)
  /// meets an A node of this level: fewer tests, more (still conservative) cells.
  int a_level = 0;
  /// Descend B alone and prune each B node with A's DistanceBound instead of
  /// descending A (a_level is then unused): a cell is reported unless the bound
  /// proves its sphere farther than reach_mm from every voxel cube of A. Still
  /// every point of B's surface within reach_mm of A's surface lies in a
  /// reported cell (that point is in the cell's sphere, A's surface in A's voxel
  /// cubes), with no A traversal at all; the cells may differ from the pair
  /// descent's (no grown-cube test). Falls back to the pair descent when A has
  /// no bound.
  bool distance_bound = false;
  /// With distance_bound: prune against this bound (in A's frame) instead of
  /// A's own, e.g. one over only the voxels of A where some value of interest
  /// can occur; reach_mm then counts from its cubes. Null: A's bound.
  const DistanceBound* a_bound = nullptr;
  /// With distance_bound (any sphere mode): per B node, a sphere (centre in
  /// B's frame, radius w) holding what the caller looks for in it, e.g. the
  /// oracle's surface samples, tested instead of the node's voxel-cube sphere
  /// (tighter: the samples lie on the surface, the cubes stick out of it);
  /// w < 0: nothing in the node, never reported. Every such point within
  /// reach_mm of A's voxel cubes lies in a reported cell. Null: B's spheres.
  const Eigen::Vector4f* b_spheres = nullptr;
};
struct CellResult {
  std::vector<std::uint32_t> cells_b;  ///< octree node indices of B, in traversal order
  std::size_t node_tests = 0;          ///< sphere-pair tests, or bound tests (distance_bound)
  std::size_t leaf_tests = 0;
};
/// Thread-safe (per-thread scratch). Throws std::invalid_argument like Collide.
void CollectCells(const SphereTree& a, const SphereTree& b, const Eigen::Isometry3d& X_AB,
                  const CellRequest& request, CellResult* result);

/// Exact separating-axis test of two cubes grown by `grow` (>= 0) on each face:
/// cube A axis-aligned in A with centre c_a and half-edge h_a, cube B with
/// centre c_b (in A), axes the columns of R_AB and half-edge h_b. Exposed for tests.
bool GrownCubesOverlap(const Eigen::Vector3d& c_a, double h_a, const Eigen::Vector3d& c_b,
                       double h_b, const Eigen::Matrix3d& R_AB, double grow);

}  // namespace occlude::collision
