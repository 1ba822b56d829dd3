// JawOracle construction: the two jaws' sides and the arch frame concurrently, and the lower
// jaw's side: its sphere tree, its narrow-band distance field, the field bound (the band cells
// where the field takes the values queries look for) and the row index of its interior runs.
// The upper's side is in oracle_samples.cpp.
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "occlude/collision/oracle.h"
#include "oracle_trees.h"
#include "parallel.h"

namespace occlude::collision {
namespace {

void CheckOptions(const OracleOptions& options) {
  if (std::isnan(options.field_bound_mm) || !(options.field_bound_depth_mm >= 0.0) ||
      !std::isfinite(options.field_bound_depth_mm)) {
    throw std::invalid_argument(
        "OracleOptions.field_bound_mm must not be NaN (negative: no field bound) and "
        "field_bound_depth_mm must be "
        "finite and >= 0");
  }
  if (options.threads < 0) {
    throw std::invalid_argument("OracleOptions.threads must be >= 0 (0 = every core), got " +
                                std::to_string(options.threads));
  }
}

}  // namespace

const char* ToString(AccuracyLevel level) {
  switch (level) {
    case AccuracyLevel::kVoxel:
      return "voxel";
    case AccuracyLevel::kSubVoxel:
      return "subvoxel";
    case AccuracyLevel::kExact:
      return "exact";
  }
  return "?";
}

JawOracle::JawOracle(std::shared_ptr<const io::TriangleMesh> lower_L,
                     std::shared_ptr<const io::TriangleMesh> upper_U, const OracleOptions& options)
    : options_(options) {
  CheckOptions(options);
  const auto start = std::chrono::steady_clock::now();
  const int threads = detail::ResolveThreads(options.threads);
  // The two jaws' sides write disjoint members (oracle.h); the arch frame only reads meshes.
  detail::RunConcurrently(
      threads,
      {[&] { BuildLowerSide(lower_L, threads); }, [&] { BuildUpperSide(upper_U, threads); },
       [&] { arch_ = options.arch ? *options.arch : EstimateArchFrame(*lower_L, *upper_U); }});
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void JawOracle::BuildLowerSide(std::shared_ptr<const io::TriangleMesh> lower_L, int threads) {
  // Its distance bound: PrepareCell, Reach.
  lower_ = SphereTree::Build(
      lower_L, detail::OracleTreeOptions(options_, detail::OracleJaw::kLower, threads));
  NarrowBandOptions sdf_options;
  sdf_options.dilation_voxels = options_.sdf_dilation_voxels;
  sdf_options.threads = threads;
  sdf_ = NarrowBandSdf::Build(std::move(lower_L), lower_.grid(), sdf_options);
  BuildFieldBound(threads);
  BuildInteriorRows();
}

void JawOracle::BuildFieldBound(int threads) {
  if (options_.field_bound_mm < 0.0) return;
  // Widened by a margin far above float rounding in the trilinear values (a
  // rounded value may fall an ulp outside its voxel's corner range).
  constexpr double kMarginMm = 1e-5;
  // Cells of voxel / split (see FieldBoundSplit); with half-voxel cells,
  // levels 0, 1, 2 and 4 of the bound keep its coarsest cap as far out (in
  // mm) as the default levels 0, 1 and 3 of whole voxels.
  const int split = FieldBoundSplit(options_.voxel_size_mm);
  field_bound_ = DistanceBound::Build(
      sdf_.BandCellsWithin(static_cast<float>(options_.field_bound_depth_mm + kMarginMm),
                           static_cast<float>(options_.field_bound_mm + kMarginMm), split, threads),
      DistanceBound::kMaxVoxels,
      split == 2 ? std::vector<int>{0, 1, 2, 4} : DistanceBound::DefaultLevels(), threads);
}

void JawOracle::BuildInteriorRows() {
  // Row index of the lower's interior runs (sorted by z, then y).
  const VoxelGrid& lower_grid = lower_.grid();
  if (lower_grid.interior_runs.empty()) return;
  const auto ny = static_cast<std::size_t>(lower_grid.dims.y());
  interior_row_begin_.assign(ny * static_cast<std::size_t>(lower_grid.dims.z()) + 1, 0);
  for (const VoxelRun& r : lower_grid.interior_runs) {
    ++interior_row_begin_[static_cast<std::size_t>(r.y) + ny * static_cast<std::size_t>(r.z) + 1];
  }
  for (std::size_t i = 0; i + 1 < interior_row_begin_.size(); ++i)
    interior_row_begin_[i + 1] += interior_row_begin_[i];
  BoundInterior();
}

void JawOracle::BoundInterior() {
  const VoxelGrid& grid = lower_.grid();
  if (grid.interior_runs.empty()) {  // the empty box
    interior_lo_L_ = Eigen::Vector3d::Constant(1.0);
    interior_hi_L_ = Eigen::Vector3d::Constant(-1.0);
    return;
  }
  Eigen::Vector3i lo = Eigen::Vector3i::Constant(std::numeric_limits<int>::max());
  Eigen::Vector3i hi = Eigen::Vector3i::Constant(std::numeric_limits<int>::min());
  for (const VoxelRun& r : grid.interior_runs) {
    lo = lo.cwiseMin(Eigen::Vector3i(r.x_begin, r.y, r.z));
    hi = hi.cwiseMax(Eigen::Vector3i(r.x_end - 1, r.y, r.z));
  }
  // Voxel v's cube is [origin + s v, origin + s (v + 1)]; one voxel more on every side.
  interior_lo_L_ = grid.origin_F + grid.voxel_size_mm * (lo.cast<double>().array() - 1.0).matrix();
  interior_hi_L_ = grid.origin_F + grid.voxel_size_mm * (hi.cast<double>().array() + 2.0).matrix();
}

std::size_t JawOracle::MemoryBytes() const {
  return lower_.stats().total_bytes() + upper_.stats().total_bytes() + sdf_.MemoryBytes() +
         field_bound_.MemoryBytes() + sample_p_U_.capacity() * sizeof(Eigen::Vector3f) +
         sample_offset_U_.capacity() * sizeof(Eigen::Vector4f) +
         sample_area_.capacity() * sizeof(float) +
         component_samples_.capacity() * sizeof(ComponentSamples) +
         interior_row_begin_.capacity() * sizeof(std::uint32_t) +
         sample_part_.capacity() * sizeof(std::int32_t) +
         voxel_sample_begin_.capacity() * sizeof(std::uint32_t) +
         voxel_centroid_U_.capacity() * sizeof(Eigen::Vector3f) +
         (voxel_area_.capacity() + voxel_part_.capacity() + cell_radius_.capacity()) * 4 +
         cell_center_U_.capacity() * sizeof(Eigen::Vector3f) +
         voxel_sphere_U_.capacity() * sizeof(Eigen::Vector4f) +
         node_sample_sphere_U_.capacity() * sizeof(Eigen::Vector4f) +
         (node_leaf_begin_.capacity() + node_leaf_end_.capacity()) * sizeof(std::uint32_t);
}

}  // namespace occlude::collision
