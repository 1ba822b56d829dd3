// The region of interest of a jaw pair: the parts of each jaw that can come near the other
// anywhere over a pose search, so that the oracles model only those (crowns near the occlusal
// plane) and not the base, the palate or the gingiva far from the bite.
//
// Contract: a triangle is dropped only when it is proved farther than the reach R = band + D
// from the other jaw at the start pose (D bounds any upper point's displacement over the
// search bounds; band is OracleReadRadiusMm), one O(1) DistanceBound probe per triangle; a
// closed component of the lower jaw is kept whole. At every pose within the bounds an oracle
// on the cut jaws then gives the answers of one on the whole jaws, up to float rounding. The
// argument (the reach, the selection, the open borders) is in docs/region-of-interest.md.
//
// Frames and units: lower in L, upper in U, mm; bounds in mm and degrees.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "occlude/collision/oracle.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::collision {

struct RegionOfInterestRequest {
  /// Start pose of U in L; the bounds are about it.
  Eigen::Isometry3d X_LU_start = Eigen::Isometry3d::Identity();
  /// Rotation pivot in L at the start pose.
  Eigen::Vector3d pivot_L = Eigen::Vector3d::Zero();
  /// Per-DOF bounds relative to the start pose, order tx, ty, tz (mm, in L), rx, ry, rz (deg,
  /// rotation vector in L about the pivot), as planner::PlanRequest's lower/upper bounds.
  std::array<double, 6> bound_min{{-3, -3, -3, -5, -5, -5}};
  std::array<double, 6> bound_max{{3, 3, 3, 5, 5, 5}};
  /// Locked DOFs stay at the start value (their bounds are ignored).
  std::array<bool, 6> locked{};
  /// The farthest any query reads the other jaw around a point of its own jaw (mm, >= 0):
  /// OracleReadRadiusMm of the widest oracle that will be built on the region.
  double band_mm = 3.0;
  /// Voxel size of the selection's distance bounds (mm, > 0): smaller is tighter near the
  /// jaws and costs more; the bound's slack at distance R is about R / 5 either way.
  double voxel_size_mm = 0.5;
};

/// One jaw cut down to the region: its triangles (in the whole mesh's order), their vertices
/// plus the whole mesh's extreme vertices along each axis, unused when not kept (so that
/// Voxelize, which frames its grid by the vertices' bounds, gives the sub-mesh the whole mesh's
/// grid frame), and every part of the whole mesh (so part indices and tooth numbers are
/// unchanged).
struct RegionMesh {
  std::shared_ptr<const io::TriangleMesh> mesh;
  std::vector<std::uint32_t> original_triangle;  ///< sub-mesh triangle -> whole-mesh triangle
};

struct RegionOfInterestStats {
  double band_mm = 0.0;          ///< as requested
  double displacement_mm = 0.0;  ///< D: the largest displacement of an upper point over the bounds
  double reach_mm = 0.0;         ///< R = band + D
  std::size_t lower_kept = 0, lower_total = 0;  ///< triangles
  std::size_t upper_kept = 0, upper_total = 0;
  double seconds = 0.0;  ///< wall time of the selection
};

struct RegionOfInterest {
  RegionMesh lower;  ///< in L
  RegionMesh upper;  ///< in U
  RegionOfInterestStats stats;
};

/// D of the header comment for the upper jaw (frame U) at request.X_LU_start. Throws
/// std::invalid_argument for non-finite bounds, pose or pivot.
double MaxDisplacementMm(const io::TriangleMesh& upper_U, const RegionOfInterestRequest& request);

/// Selects the region of interest (see the header comment). Throws std::invalid_argument for
/// a null mesh, a negative or non-finite band, a non-positive voxel size or bad bounds.
RegionOfInterest ComputeRegionOfInterest(const std::shared_ptr<const io::TriangleMesh>& lower_L,
                                         const std::shared_ptr<const io::TriangleMesh>& upper_U,
                                         const RegionOfInterestRequest& request);

/// The regions of one pair, start pose and bounds for several bands (a schedule's voxel
/// sizes): the jaws' distance bounds, the upper at the start pose and the lower's closed
/// components are made once, at construction; Select(band) then gives exactly
/// ComputeRegionOfInterest of the request with that band. Select is const and thread-safe.
class RegionSelector {
 public:
  /// `request.band_mm` is ignored. Throws as ComputeRegionOfInterest.
  RegionSelector(std::shared_ptr<const io::TriangleMesh> lower_L,
                 std::shared_ptr<const io::TriangleMesh> upper_U,
                 const RegionOfInterestRequest& request);
  ~RegionSelector();
  RegionSelector(RegionSelector&&) noexcept;
  RegionSelector& operator=(RegionSelector&&) noexcept;

  /// The region for `band_mm` (stats.seconds: this selection's wall time).
  RegionOfInterest Select(double band_mm) const;
  /// Wall seconds of the construction.
  double seconds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The region a selection kept, made again from its kept triangles (each jaw's
/// RegionMesh::original_triangle, whole-mesh indices in increasing order) and its stats: the
/// same sub-meshes, vertex for vertex, as the selection gave (a saved selection, read back).
/// The stats' kept counts are set from the lists. Throws std::invalid_argument for a null mesh
/// or a list that is not increasing or names a triangle the mesh does not have.
RegionOfInterest RegionOfKept(const std::shared_ptr<const io::TriangleMesh>& lower_L,
                              const std::shared_ptr<const io::TriangleMesh>& upper_U,
                              std::vector<std::uint32_t> lower_kept,
                              std::vector<std::uint32_t> upper_kept,
                              const RegionOfInterestStats& stats);

/// 16 hex digits that change whenever the selection's code does (a hash of its sources: the
/// selection, the voxelization and distance bounds it builds on, the mesh transform; made by the
/// build): what a saved selection is keyed by besides the meshes and the request.
const char* RegionSelectionCodeVersion();

/// The farthest (mm) a JawOracle built with `options` reads the lower jaw around an upper
/// sample (or the lower jaw's surface voxels, its field corners' closest points and their
/// pseudo-normals), at every accuracy level, for requests whose exact-level search reach
/// (max of contact band, penetration search and residual band) is at most `exact_reach_mm`:
///   sqrt(3) s max(k + 3, ceil(exact_reach / s) + 2), s = voxel size, k = field dilation.
/// Sub-voxel: the sample's band voxel is decided by the surface voxels within k voxels per
/// axis (their cubes within sqrt(3) (k + 1) s of the sample), a corner's closest point is
/// within sqrt(3) (k + 1) s of the corner (a surface voxel within k of its voxel holds a
/// surface point), the corner within sqrt(3) s of the sample: sqrt(3) (k + 2) s. Voxel level:
/// the voxel centroid stands up to sqrt(3) s off the surface: + sqrt(3) s. Exact level:
/// NarrowBandSdf::Exact scans the surface voxels within ceil(reach / s) + 1 voxels.
double OracleReadRadiusMm(const OracleOptions& options, double exact_reach_mm);

/// True when every upper vertex (frame U) is displaced by at most `displacement_mm` between
/// X_LU_start and X_LU (exact over the vertices): the poses a region of that displacement
/// answers for, whether or not they lie within the bounds it was computed for.
bool RegionCoversPose(const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU_start,
                      const Eigen::Isometry3d& X_LU, double displacement_mm);

}  // namespace occlude::collision
