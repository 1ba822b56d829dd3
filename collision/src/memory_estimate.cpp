// Memory estimates of the collision structures before they are built (see
// memory_estimate.h). Each term names the arrays it stands for; the byte
// counts are those of the current storage (sphere_tree.h, octree.h,
// signed_distance.h, oracle.h), the brick-structure coefficients are fitted.
#include "occlude/collision/memory_estimate.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "oracle_trees.h"

namespace occlude::collision {
namespace {

// Surface voxels per A / s^2 (the voxel grid's own model).
constexpr double kSurfacePerArea = 1.5;
// Octree nodes per surface voxel: a surface has ~4 children per parent, so
// 1 + 1/4 + 1/16 + ... = 4/3.
constexpr double kNodesPerSurface = 4.0 / 3.0;
// Octree bytes per node: coord (3 x int32), first_child (uint32), child_mask.
constexpr double kOctreeNodeBytes = 12 + 4 + 1;
// DistanceBound bytes per A / s^2: 8^3-byte bricks over a band of 7 voxels
// each side at levels 0, 1 and 3, plus the hash (fitted: 29-39 on the
// synthetic pair and a-bite, 0.1-0.8 mm).
constexpr double kBoundBytesPerArea = 34.0;
constexpr double kBoundMinBytes = 3 * 8 * 512;  // a few bricks per level, whatever the size
// Narrow band: band voxels per surface voxel and dilation layer, bytes per
// band voxel (5^3 float corners per 4^3-voxel brick, partly filled, the band's
// brick set and hash) and per surface voxel (the surface brick set, sparser);
// fitted on the same meshes with dilations 0 and 2.
constexpr double kBandVoxelsPerLayer = 0.9;
constexpr double kBandVoxelBytes = 14.0;
constexpr double kSurfaceBrickBytes = 22.0;
// Per triangle in the field: pseudo-normals (face 12, 3 edges 36, corners
// 12), the packed triangle (13 doubles) and its original index.
constexpr double kSdfTriangleBytes = 12 + 36 + 12 + 104 + 4;
constexpr double kSdfVertexBytes = 12;  // vertex pseudo-normal (3 floats)
// Oracle samples: position (3 floats), offset about its cell's grid point (4
// floats), area, part; while building, each raw sample is 40 bytes plus its voxel
// index (8), in vectors that grow by doubling.
constexpr double kSampleBytes = 12 + 16 + 4 + 4;
// Before merging: sample (40) and its voxel (8) with vector growth, and the merge's sort key (24).
constexpr double kRawSampleBytes = 1.5 * (40 + 8) + 24;
// Per upper surface voxel: sample range, centroid, area, part, bounding sphere (4 floats).
constexpr double kOracleVoxelBytes = 4 + 12 + 4 + 4 + 16;
// Per upper node: leaf range (2 x uint32); per level-1 cell: centre and radius;
// per node above the leaves: its samples' sphere (4 floats).
constexpr double kOracleNodeBytes = 8 + 16.0 / 4.0 + 16.0 / 6.0;
// Voxelize's transient (the (voxel, triangle) pair list and its sort buffer)
// over its result.
constexpr double kVoxelizeTransient = 2.5;

std::size_t ToBytes(double bytes) {
  if (!(bytes > 0.0)) return 0;
  return static_cast<std::size_t>(std::min(bytes, 1e18));
}

double MeshBytes(const io::TriangleMesh& mesh) {
  // vertices (3 doubles), triangles (3 int32), face normals (3 doubles), part index.
  return 24.0 * static_cast<double>(mesh.num_vertices()) +
         (12.0 + 24.0 + 4.0) * static_cast<double>(mesh.num_triangles());
}

double SurfaceVoxels(const io::TriangleMesh& mesh, double s) {
  return 1.0 + kSurfacePerArea * mesh.SurfaceArea() / (s * s);
}

// The upper samples JawOracle takes before merging: triangle t is split into
// k^2 pieces, k = ceil(longest edge / spacing) (at least 1).
double SampleCount(const io::TriangleMesh& mesh, double spacing) {
  double n = 0.0;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d &a = mesh.corner(t, 0), &b = mesh.corner(t, 1), &c = mesh.corner(t, 2);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const double k = std::max(1.0, std::ceil(longest / spacing));
    n += k * k;
  }
  return n;
}

MemoryEstimate Make(double resident, double transient) {
  return {ToBytes(resident), ToBytes(resident + transient)};
}

// Reads one unsigned number from a cgroup file; 0 when absent or "max".
std::size_t ReadLimit(const char* file) {
  std::ifstream in(file);
  std::string text;
  if (!(in >> text) || text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
    return 0;
  try {
    return static_cast<std::size_t>(std::stoull(text));
  } catch (const std::exception&) {
    return 0;
  }
}

}  // namespace

MemoryEstimate& MemoryEstimate::operator+=(const MemoryEstimate& other) {
  // Structures are built one after the other: the peaks do not add, the
  // residents do (each peak happens on top of what was built before).
  peak_bytes = std::max(peak_bytes + other.resident_bytes, resident_bytes + other.peak_bytes);
  resident_bytes += other.resident_bytes;
  return *this;
}

MemoryEstimate EstimateSphereTreeMemory(const io::TriangleMesh& mesh,
                                        const SphereTreeOptions& options) {
  const double s = options.voxelize.voxel_size_mm;
  const double grid = static_cast<double>(EstimateVoxelizeBytes(mesh, options.voxelize));
  const double nodes = kNodesPerSurface * SurfaceVoxels(mesh, s);
  double bytes = grid + MeshBytes(mesh) + kOctreeNodeBytes * nodes;
  if (options.build_explicit) bytes += static_cast<double>(sizeof(ExplicitNode)) * nodes;
  if (options.build_distance_bound) {
    bytes += std::max(kBoundMinBytes, kBoundBytesPerArea * mesh.SurfaceArea() / (s * s));
  }
  return Make(bytes, kVoxelizeTransient * grid);
}

MemoryEstimate EstimateNarrowBandSdfMemory(const io::TriangleMesh& mesh, double voxel_size_mm,
                                           int dilation_voxels) {
  VoxelizeOptions surface_only;
  surface_only.voxel_size_mm = voxel_size_mm;
  surface_only.classify_proximity = false;
  surface_only.classify_interior = false;
  // The field keeps the grid's triangle lists (offsets and indices).
  const double lists = static_cast<double>(EstimateVoxelizeBytes(mesh, surface_only));
  const double surface = SurfaceVoxels(mesh, voxel_size_mm);
  const double band = surface * (1.0 + kBandVoxelsPerLayer * 2.0 * std::max(dilation_voxels, 0));
  const double bytes = lists + kBandVoxelBytes * band + kSurfaceBrickBytes * surface +
                       kSdfTriangleBytes * static_cast<double>(mesh.num_triangles()) +
                       kSdfVertexBytes * static_cast<double>(mesh.num_vertices());
  return Make(bytes, kVoxelizeTransient * lists);
}

MemoryEstimate EstimateOracleMemory(const io::TriangleMesh& lower_L,
                                    const io::TriangleMesh& upper_U, const OracleOptions& options) {
  MemoryEstimate total = EstimateSphereTreeMemory(
      lower_L, detail::OracleTreeOptions(options, detail::OracleJaw::kLower, 1));
  total += EstimateSphereTreeMemory(
      upper_U, detail::OracleTreeOptions(options, detail::OracleJaw::kUpper, 1));
  // The field reuses the lower tree's grid, so its lists are not a new transient.
  MemoryEstimate field =
      EstimateNarrowBandSdfMemory(lower_L, options.voxel_size_mm, options.sdf_dilation_voxels);
  field.peak_bytes = field.resident_bytes;
  total += field;
  // The field bound: a distance bound over a set a few voxels thicker than the
  // lower's surface voxels, in cells of voxel / FieldBoundSplit: about the
  // size of the lower tree's own bound at that cell size (a-bite-3shape at
  // 0.2 mm: the oracle grew by 21 MB when the cells were halved).
  if (options.field_bound_mm >= 0.0) {
    const double s = options.voxel_size_mm / JawOracle::FieldBoundSplit(options.voxel_size_mm);
    total +=
        Make(std::max(kBoundMinBytes, kBoundBytesPerArea * lower_L.SurfaceArea() / (s * s)), 0.0);
  }
  const double spacing = options.sample_spacing_mm > 0 ? options.sample_spacing_mm : 0.3;
  const double raw_samples = SampleCount(upper_U, spacing);
  // Merged: at most one per occupied sub-cell of the voxels (edge voxel / k).
  const double k = std::max(1.0, std::ceil(options.voxel_size_mm / spacing - 1e-9));
  const double samples = std::min(raw_samples, SurfaceVoxels(upper_U, options.voxel_size_mm / k));
  const double voxels = SurfaceVoxels(upper_U, options.voxel_size_mm);
  const double resident = kSampleBytes * samples + kOracleVoxelBytes * voxels +
                          kOracleNodeBytes * kNodesPerSurface * voxels;
  total += Make(resident, kRawSampleBytes * raw_samples);
  return total;
}

std::size_t PhysicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  std::size_t bytes = pages > 0 && page_size > 0
                          ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(page_size)
                          : 0;
  for (const char* file :
       {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    const std::size_t limit = ReadLimit(file);
    if (limit > 0 && (bytes == 0 || limit < bytes)) bytes = limit;
  }
  return bytes;
}

std::size_t DefaultMemoryBudgetBytes() {
  const std::size_t physical = PhysicalMemoryBytes();
  return physical > 0 ? physical / 4 : std::size_t{1} << 30;
}

double SmallestFittingVoxelMm(const std::function<std::size_t(double voxel_mm)>& peak_bytes,
                              double from_mm, double max_mm, std::size_t budget_bytes) {
  if (peak_bytes(from_mm) <= budget_bytes) return from_mm;
  if (peak_bytes(max_mm) > budget_bytes) return std::numeric_limits<double>::infinity();
  double lo = from_mm, hi = max_mm;  // peak(lo) > budget >= peak(hi)
  while (hi > lo * 1.005) {
    const double mid = std::sqrt(lo * hi);
    (peak_bytes(mid) > budget_bytes ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace occlude::collision
