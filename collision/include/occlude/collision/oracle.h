// The contact and penetration oracle: for a pose X_LU of the upper jaw U in the
// lower jaw's frame L, how much the jaws touch, how deep they interpenetrate,
// and where; fast enough for an optimizer's inner loop and a haptic loop.
//
// How: the upper surface is sampled (points with area weights, grouped by the
// upper's surface voxels). The one-sided sphere-tree descent (CollectCells)
// finds the upper octree cells whose samples' bounding spheres come within
// reach of the lower's voxels; only the samples of those cells are evaluated, against the lower
// jaw's signed distance (narrow-band field, or exact triangles). No query
// touches all samples, voxels or triangles.
//
// Sign convention: signed distance d of an upper sample to the lower surface,
// positive outside the lower jaw (the side its outward normals point to),
// negative inside (penetration), from surface orientation (pseudo-normals), so
// open scans work. Contact: 0 <= d <= contact_band_mm. Units mm and mm^2.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <vector>

#include "occlude/collision/arch_frame.h"
#include "occlude/collision/collide.h"
#include "occlude/collision/signed_distance.h"
#include "occlude/collision/sphere_tree.h"
#include "occlude/io/content_hash.h"

namespace occlude::collision {

enum class AccuracyLevel {
  kVoxel,  ///< one sample per upper voxel, lower distance at the voxel centre: error ~ voxel size
  kSubVoxel,  ///< every sample, trilinear narrow-band distance: error ~ 0.01 mm at 0.2 mm voxels
  kExact,     ///< every sample, exact closest lower triangle with pseudo-normal sign
};
const char* ToString(AccuracyLevel level);

struct OracleOptions {
  double voxel_size_mm = 0.2;  ///< voxel size of both trees and the lower's distance field
  /// Upper samples about this far apart: triangles longer than it are split
  /// into pieces with edges below it, and the samples of finer triangles are
  /// merged, one per part in each sub-cell of an upper voxel split into k^3
  /// (k = ceil(voxel / spacing)): the member nearest their area-weighted
  /// centroid, carrying their area. Scanned jaws are triangulated more finely
  /// than the oracle needs (a-bite-3shape: 0.06 mm^2 per triangle, 663k
  /// unmerged samples at 0.3 mm, 225k merged with 0.2 mm voxels).
  double sample_spacing_mm = 0.3;
  int sdf_dilation_voxels = 2;  ///< narrow band of the lower's distance field, in voxels
  int cell_level = 1;           ///< octree level of the upper cells evaluated as a unit
  int lower_level = 1;          ///< the broad phase descends the lower tree down to this level
  /// Broad phase against the lower's DistanceBound (CellRequest::distance_bound):
  /// the upper tree alone is descended, O(1) per node; false = pair descent.
  bool distance_bound = true;
  /// Sub-voxel and voxel-level queries whose outer band (the contact band, or
  /// the residual band with residuals) is at most field_bound_mm and whose
  /// penetration search is at most field_bound_depth_mm prune the upper tree
  /// against the lower's field bound: the surface voxels and the cells of the
  /// band voxels (each split JawOracle::FieldBoundSplit(voxel) ways per axis)
  /// where the field takes values in [-depth, field_bound_mm]. Every sample
  /// whose value lies in that range is in one of them, so the broad phase
  /// needs no reach and reports no cell that lies wholly beyond the contact
  /// band outside the lower jaw or wholly deeper than the search inside.
  /// Other queries (exact level, cull = false, wider bands) use the surface
  /// voxels and the reach. Negative field_bound_mm: no field bound (not built).
  double field_bound_mm = 0.1;
  double field_bound_depth_mm = 0.3;
  /// Build what queries between the two trees need besides the oracle's own: both trees'
  /// explicit spheres and the upper's distance bound (the IST pair queries, Collide and
  /// CollectCells on lower_tree() and upper_tree(), and the pair descent of distance_bound =
  /// false). The oracle's queries never read them with distance_bound = true (the upper's
  /// descent takes its samples' spheres, against the lower's bounds): false saves their build
  /// and memory (a-bite-3shape at 0.2 mm: 61 of 216 MB); pair queries on the trees then fall
  /// back to implicit spheres.
  bool tree_queries = true;
  std::optional<ArchFrame> arch;  ///< default: EstimateArchFrame with U as given
  /// Threads of the build (0 = every core): the two jaws' structures and the independent
  /// stages run concurrently, the heaviest loops in fixed blocks. The oracle is the same,
  /// bit for bit, for any count; it only changes how long the build takes.
  int threads = 0;
};

struct OracleRequest {
  AccuracyLevel level = AccuracyLevel::kSubVoxel;
  double contact_band_mm = 0.1;        ///< contact: 0 <= d <= band
  double penetration_search_mm = 0.3;  ///< depths are measured up to here (and to the field's band)
  bool residuals = false;              ///< fill OracleResult::residuals
  double residual_band_mm = 0.5;       ///< residuals for samples with d <= this
  Eigen::Vector3d pivot_L = Eigen::Vector3d::Zero();  ///< rotation pivot of the gradients, mm in L
  bool keep_points = true;                            ///< fill contacts / penetrations point lists
  /// Skip the upper cells and voxels whose samples the field proves to count
  /// for nothing (farther out than the contact band, or the residual band with
  /// residuals); every total, list and residual is the same either way. false:
  /// every sample of every broad-phase cell is evaluated (several times
  /// slower), which also makes min_distance_mm exact beyond the contact band.
  bool cull = true;
};

/// One evaluated upper sample (position in L at the queried pose).
struct SurfacePoint {
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();
  double distance_mm = 0.0;  ///< signed distance to the lower surface
  double area_mm2 = 0.0;     ///< upper surface area the sample stands for
  std::int32_t part = 0;     ///< upper part index (tooth) of the sample
};

/// Totals per upper part (tooth when the jaw came in parts).
struct PartTotals {
  std::int32_t part = 0;
  int tooth_number = 0;
  double contact_area_mm2 = 0.0;
  std::size_t contact_samples = 0;
  double penetration_area_mm2 = 0.0;
  double max_penetration_mm = 0.0;
};

/// Residual for least squares: d and its derivative with respect to the pose
/// update X_LU' = [pivot + Exp(w) (X_LU p - pivot) + t]: columns 0-2 = d/dt
/// (per mm), 3-5 = d/dw (per radian, rotation vector in L about pivot_L).
struct DistanceResidual {
  double distance_mm = 0.0;
  Eigen::Matrix<double, 1, 6> gradient = Eigen::Matrix<double, 1, 6>::Zero();
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();
  double area_mm2 = 0.0;
};

struct OracleResult {
  AccuracyLevel level = AccuracyLevel::kSubVoxel;  ///< the level actually used
  // Penetration (d < 0).
  double max_penetration_mm = 0.0;  ///< deepest measured depth (>= 0)
  double penetration_area_mm2 = 0.0;
  Eigen::Vector3d deepest_p_L = Eigen::Vector3d::Zero();
  std::size_t deep_samples = 0;  ///< samples inside the lower beyond the measured depth range
  // Contact (0 <= d <= band).
  double contact_area_mm2 = 0.0;
  std::size_t contact_samples = 0;
  /// Smallest signed distance among the evaluated samples (+inf if none).
  /// With OracleRequest::cull, samples farther out than the contact band (the
  /// residual band with residuals) may be skipped: a minimum within that band
  /// is exact, one beyond it only an upper bound (+inf when every sample was
  /// skipped). Without culling it is exact over the samples within the reach.
  double min_distance_mm = 0.0;
  double left_share = 0.0, right_share = 0.0;          ///< of contact area
  double anterior_share = 0.0, posterior_share = 0.0;  ///< of contact area
  std::vector<PartTotals> parts;                       ///< one entry per upper part
  std::vector<SurfacePoint> contacts;                  ///< contact samples (if keep_points)
  std::vector<SurfacePoint> penetrations;              ///< penetrating samples (if keep_points)
  /// The deep samples one by one (if keep_points), distance_mm = -(penetration_search_mm +
  /// the field's band): at least that deep. Not those of upper pieces wholly inside the lower
  /// (counted per piece), so deep_points.size() <= deep_samples.
  std::vector<SurfacePoint> deep_points;
  std::vector<DistanceResidual> residuals;  ///< if requested
  // Work done.
  std::size_t cells = 0;
  std::size_t samples_evaluated = 0;  ///< samples (voxel centroids at voxel level) looked up
  std::size_t node_tests = 0;
};

/// The oracle for one jaw pair: both sphere trees, the lower's distance field
/// and the upper's samples, built once; Query() is const and thread-safe.
class JawOracle {
 public:
  /// The field bound's cells: the voxels split this many ways per axis, 2
  /// unless that would make them finer than 0.1 mm (then 1). Half-voxel cubes
  /// reach at most half a voxel diagonal beyond the band (0.17 mm at 0.2 mm
  /// voxels) instead of a whole one, so fewer upper cells come within reach
  /// (a-bite-3shape at 0.2 mm, +0.2 mm apart: 1305 -> 635 cells and 153 ->
  /// 123 us; build +0.65 s, +21 MB). At 0.1 mm voxels the whole voxel is
  /// already that fine, and halving it cost 8 s of build and 93 MB.
  static int FieldBoundSplit(double voxel_size_mm) { return voxel_size_mm >= 0.2 - 1e-9 ? 2 : 1; }

  JawOracle(std::shared_ptr<const io::TriangleMesh> lower_L,
            std::shared_ptr<const io::TriangleMesh> upper_U, const OracleOptions& options = {});

  void Query(const Eigen::Isometry3d& X_LU, const OracleRequest& request,
             OracleResult* result) const;

  const SphereTree& lower_tree() const { return lower_; }
  const SphereTree& upper_tree() const { return upper_; }
  const NarrowBandSdf& lower_sdf() const { return sdf_; }
  const ArchFrame& arch() const { return arch_; }
  std::size_t num_samples() const { return sample_area_.size(); }
  /// The upper samples' positions in U, mm, grouped by upper surface voxel (the order every
  /// query evaluates them in); a pose X_LU places them in L (X_LU * p_U). For peers that
  /// sample another distance field at exactly the oracle's points (`occlude bench`).
  const std::vector<Eigen::Vector3f>& samples_U() const { return sample_p_U_; }
  /// The upper surface area each sample stands for, mm^2 (parallel to samples_U()).
  const std::vector<float>& sample_areas_mm2() const { return sample_area_; }
  double sample_spacing_mm() const { return options_.sample_spacing_mm; }
  double build_seconds() const { return build_seconds_; }
  std::size_t MemoryBytes() const;
  /// Whether the lower grid classes p_L's voxel Interior: lower_tree().grid().IsInterior(
  /// VoxelOf(p_L)), read from the runs of the voxel's row alone.
  bool LowerInterior(const Eigen::Vector3d& p_L) const;

 private:
  friend struct detail::OracleCodec;
  JawOracle() = default;  ///< empty, for the codec to fill (oracle_file.h)
  struct QueryContext;    // per-query constants and the field sampler (oracle_query.cpp)
  /// The broad phase's request for `request`: against the field bound when it applies, else
  /// the lower's voxels with the request's reach (oracle_query.cpp).
  CellRequest BroadPhase(const OracleRequest& request) const;
  /// Sets q's per-cell values for upper cell `node` (q->cell already at its centre's grid
  /// point); false when its samples cannot count (culled).
  bool PrepareCell(std::uint32_t node, std::uint32_t level_begin, QueryContext* q) const;
  /// Evaluates the samples (or, at voxel level, the voxel centroids) of one
  /// upper cell, described by q (oracle_evaluate.cpp).
  void EvaluateCell(std::uint32_t node, QueryContext* q, OracleResult* result) const;
  /// The sub-voxel level of EvaluateCell over the cell's voxels [first, last).
  void EvaluateSubVoxel(std::uint32_t first, std::uint32_t last, QueryContext* q,
                        OracleResult* result) const;
  /// Adds one sample at signed distance d (gradient only needed for residuals).
  void Accumulate(const Eigen::Vector3d& p_L, double d, const Eigen::Vector3d& grad, double area,
                  std::int32_t part, const OracleRequest& request, OracleResult* result) const;
  /// An unknown sample (outside the field's band, or no triangle within reach).
  void CountIfDeep(const Eigen::Vector3d& p_L, double area, std::int32_t part,
                   const OracleRequest& request, OracleResult* result) const;
  /// Counts one deep sample (and lists it with keep_points).
  void AddDeep(const Eigen::Vector3d& p_L, double area, std::int32_t part,
               const OracleRequest& request, OracleResult* result) const;
  /// Upper sample i, unknown to the field: deep when `interior` (its voxel's unknown samples all
  /// lie inside the lower), else classified on its own.
  void AddUnknownSample(std::uint32_t i, bool interior, const QueryContext& q,
                        OracleResult* result) const;
  // No upper cell came within reach of the lower surface: the upper lies wholly outside the
  // lower or (some of its connected components) wholly inside a closed lower component. One
  // interior test per upper component tells which; the samples of those inside count as deep.
  void CountNestedPieces(const Eigen::Isometry3d& X_LU, OracleResult* result) const;

  // Construction (oracle_build.cpp: the lower jaw's side; oracle_samples.cpp: the upper's).
  // The two sides write disjoint members and run concurrently.
  void BuildLowerSide(std::shared_ptr<const io::TriangleMesh> lower_L, int threads);
  void BuildFieldBound(int threads);
  void BuildInteriorRows();
  /// interior_lo_L_ and interior_hi_L_ from the lower grid's interior runs (built or loaded).
  void BoundInterior();
  void BuildUpperSide(std::shared_ptr<const io::TriangleMesh> upper_U, int threads);
  /// The samples of the upper surface, grouped by voxel (CSR), and one per component.
  void PlaceSamples(const io::TriangleMesh& upper_U, int threads);
  void BuildVoxelSamples();
  void BuildNodeLeafRanges();
  /// Cell centres and radii, the samples' offsets and the voxels' spheres (the query's culls).
  void BuildCellSpheres();
  void BuildNodeSampleSpheres();
  void BuildSamplesSphere();

  OracleOptions options_;
  SphereTree lower_, upper_;
  NarrowBandSdf sdf_;
  DistanceBound field_bound_;  ///< OracleOptions::field_bound_mm (empty when not built)
  ArchFrame arch_;
  // Upper samples in U, grouped by upper surface voxel (CSR, voxel order).
  std::vector<Eigen::Vector3f> sample_p_U_;
  std::vector<Eigen::Vector4f>
      sample_offset_U_;  ///< p_U minus its cell's centre (cell_center_U_), w = 0
  std::vector<float> sample_area_;
  std::vector<std::int32_t> sample_part_;
  std::vector<std::uint32_t> voxel_sample_begin_;  ///< size = upper voxels + 1
  // Per upper voxel: area-weighted centroid and total area (the voxel level).
  std::vector<Eigen::Vector3f> voxel_centroid_U_;
  std::vector<float> voxel_area_;
  /// Per upper voxel: centre of its samples' bounding box minus its cell's
  /// centre (x, y, z, in U) and their largest distance from it (w).
  std::vector<Eigen::Vector4f> voxel_sphere_U_;
  std::vector<std::int32_t> voxel_part_;
  // Per upper octree node: its leaf range [first, last) (voxel indices).
  std::vector<std::uint32_t> node_leaf_begin_, node_leaf_end_;
  // Per node of the cell level (index: node - level_begin): centre of its
  // samples' bounding box in U and their largest distance from it (0: none).
  std::vector<Eigen::Vector3f> cell_center_U_;
  std::vector<float> cell_radius_;
  /// Per node at or above the cell level (nodes [0, level_end of the cell
  /// level)): its samples' bounding sphere in U (radius -1: no samples), the
  /// spheres the broad phase tests (tighter than the nodes' voxel cubes).
  std::vector<Eigen::Vector4f> node_sample_sphere_U_;
  // Per connected component of the upper surface: one of its samples and how many it has.
  struct ComponentSamples {
    std::uint32_t sample;
    std::uint32_t count;
  };
  std::vector<ComponentSamples> component_samples_;
  // The lower grid's interior runs by row: those of row (y, z) are
  // [interior_row_begin_[y + dims.y z], interior_row_begin_[that + 1]) (empty: no runs).
  std::vector<std::uint32_t> interior_row_begin_;
  // A box (L, mm) beyond which no point lies in an interior voxel: the interior voxels' box
  // grown by a voxel on every side (VoxelOf's nudge and rounding stay far within it); empty
  // (lo > hi) without interior runs. Derived from the runs (BoundInterior), not saved.
  Eigen::Vector3d interior_lo_L_ = Eigen::Vector3d::Constant(1.0);
  Eigen::Vector3d interior_hi_L_ = Eigen::Vector3d::Constant(-1.0);
  // A sphere holding every upper sample (centre in U, radius): rules out nesting at once.
  Eigen::Vector3d samples_centre_U_ = Eigen::Vector3d::Zero();
  double samples_radius_ = 0.0;
  std::vector<bool> part_is_anterior_tooth_;  ///< known from tooth numbers
  std::vector<bool> part_has_tooth_;
  double build_seconds_ = 0.0;
};

/// Adds an answer to `hash`, bit-exact: its totals, shares, deepest point, counts (samples,
/// cells, samples evaluated; not node_tests), parts, point lists and residuals. Equal hashes
/// over many queries mean bit-identical answers (determinism and saved-oracle checks).
void HashOracleResult(const OracleResult& result, io::Hasher64* hash);

// lower grid.Classify(voxel of p_L) == kInterior: the interior runs are disjoint from the other
// classes, so the runs of the voxel's row tell (there are none for open meshes). Inline: the
// queries and the planner's settle ask it per sample.
inline bool JawOracle::LowerInterior(const Eigen::Vector3d& p_L) const {
  if (interior_row_begin_.empty()) return false;
  for (int a = 0; a < 3; ++a) {  // the cheap answer for most points away from the jaw
    if (!(p_L[a] >= interior_lo_L_[a] && p_L[a] <= interior_hi_L_[a])) return false;
  }
  const VoxelGrid& grid = lower_.grid();
  const Eigen::Vector3i v = grid.VoxelOf(p_L);
  if ((v.array() < 0).any() || (v.array() >= grid.dims.array()).any()) return false;
  const std::size_t row = static_cast<std::size_t>(v.y()) +
                          static_cast<std::size_t>(grid.dims.y()) * static_cast<std::size_t>(v.z());
  for (std::uint32_t k = interior_row_begin_[row]; k < interior_row_begin_[row + 1]; ++k) {
    const VoxelRun& r = grid.interior_runs[k];
    if (v.x() < r.x_begin) return false;
    if (v.x() < r.x_end) return true;
  }
  return false;
}

}  // namespace occlude::collision
