// VoxelGrid queries and the Voxelize driver: input checks, grid placement, the
// memory estimate and guard, then the surface, proximity and interior stages
// (voxelize_surface.cpp, voxelize_proximity.cpp, voxelize_interior.cpp).
#include "occlude/collision/voxel_grid.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "occlude/collision/floor_int.h"
#include "occlude/collision/morton.h"
#include "seconds_since.h"
#include "voxelize_detail.h"

namespace occlude::collision {
namespace {

constexpr int kMaxProximityLayers = 1000;

/// x rounded up to 3 significant digits, as text (for error messages).
std::string RoundUp(double x) {
  if (!(x > 0.0) || !std::isfinite(x)) {
    std::ostringstream out;
    out << x;
    return out.str();
  }
  const double scale = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
  std::ostringstream out;
  out.precision(3);
  out << std::ceil(x / scale * (1.0 - 1e-12)) * scale;
  return out.str();
}

int Padding(const VoxelizeOptions& options) { return std::max(options.proximity_layers, 0) + 1; }

/// Voxels needed along one axis to cover [min, max] plus `pad` voxels each side.
double AxisVoxels(double min, double max, double s, int pad) {
  return std::floor(max / s) - std::floor(min / s) + 1.0 + 2.0 * pad;
}

void CheckOptions(const VoxelizeOptions& options) {
  const double s = options.voxel_size_mm;
  if (!std::isfinite(s) || s <= 0.0) {
    std::ostringstream msg;
    msg << "voxel size must be a finite number > 0 mm, got " << s;
    throw VoxelizeError(msg.str());
  }
  if (options.proximity_layers < 0 || options.proximity_layers > kMaxProximityLayers) {
    std::ostringstream msg;
    msg << "proximity_layers must be in [0, " << kMaxProximityLayers << "], got "
        << options.proximity_layers;
    throw VoxelizeError(msg.str());
  }
}

void CheckMesh(const io::TriangleMesh& mesh) {
  if (mesh.num_triangles() > std::size_t{0xffffffffu}) {
    throw VoxelizeError("too many triangles for 32-bit triangle indices");
  }
  const auto nv = static_cast<int>(mesh.num_vertices());
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    if ((mesh.triangles[t].array() < 0).any() || (mesh.triangles[t].array() >= nv).any()) {
      std::ostringstream msg;
      msg << "triangle " << t << " indexes a vertex outside 0.." << nv - 1;
      throw VoxelizeError(msg.str());
    }
  }
  for (const Eigen::Vector3d& v : mesh.vertices) {
    if (!v.allFinite()) throw VoxelizeError("mesh has a vertex with a non-finite coordinate");
  }
}

/// Places the grid around `bounds`; throws when a dimension exceeds kMortonMaxCoord.
detail::GridFrame MakeFrame(const Eigen::AlignedBox3d& bounds, const VoxelizeOptions& options) {
  const double s = options.voxel_size_mm;
  const int pad = Padding(options);
  detail::GridFrame f;
  f.s = s;
  for (int a = 0; a < 3; ++a) {
    const double n = AxisVoxels(bounds.min()[a], bounds.max()[a], s, pad);
    if (!(n <= static_cast<double>(kMortonMaxCoord))) {
      const double extent = bounds.sizes().maxCoeff();
      std::ostringstream msg;
      msg << "voxel grid too large: the mesh extent " << extent << " mm at voxel size " << s
          << " mm needs " << n << " voxels along axis "
          << "xyz"[a] << " (at most " << kMortonMaxCoord
          << "); the smallest voxel size that fits is about "
          << RoundUp(extent / (kMortonMaxCoord - 2.0 - 2.0 * pad)) << " mm";
      throw VoxelizeError(msg.str());
    }
    f.dims[a] = static_cast<int>(n);
    f.origin[a] = (std::floor(bounds.min()[a] / s) - pad) * s;
  }
  f.coord_bits = std::max(1, detail::BitWidth(static_cast<std::uint64_t>(f.dims.maxCoeff() - 1)));
  return f;
}

/// Model of the grid's size from the surface area A, the triangle count T and s
/// (coefficients fitted on spheres, boxes and the real jaws and mandible, within
/// about 25% of MemoryBytes() there): surface voxels ~ 1.5 A / s^2 (a plane of
/// unit normal n meets |n|_1 A / s^2 touching voxels, 1.5 on average); (voxel,
/// triangle) pairs add the triangles' borders ~ sqrt(A T) / s and corners ~ T;
/// proximity ~ 0.75 x layers x surface; interior runs ~ 0.1 x surface. This is
/// the size of the result; the transient peak inside Voxelize (the pair list and
/// its sort buffer) is about 2 to 2.5 times more.
struct SizeModel {
  double surface = 0.0;
  double pairs = 0.0;
  double proximity = 0.0;
  double runs = 0.0;
  double Bytes() const {
    return surface * static_cast<double>(sizeof(std::uint64_t) + sizeof(std::uint32_t)) +
           pairs * static_cast<double>(sizeof(std::uint32_t)) +
           proximity * static_cast<double>(sizeof(std::uint64_t)) +
           runs * static_cast<double>(sizeof(VoxelRun));
  }
};

SizeModel ModelSize(double area, double triangles, double s, const VoxelizeOptions& options) {
  SizeModel m;
  m.surface = 1.5 * area / (s * s);
  m.pairs = m.surface + 2.7 * std::sqrt(area * triangles) / s + 1.2 * triangles;
  if (options.classify_proximity) m.proximity = 0.75 * options.proximity_layers * m.surface;
  if (options.classify_interior) m.runs = 0.1 * m.surface;
  return m;
}

/// Smallest voxel size whose modelled size fits `budget` (infinity if none does).
double SmallestFittingVoxelSize(double area, double triangles, const VoxelizeOptions& options,
                                double budget) {
  double lo = options.voxel_size_mm, hi = lo;
  for (int n = 0; n < 200 && ModelSize(area, triangles, hi, options).Bytes() > budget; ++n) {
    hi *= 2.0;
  }
  if (ModelSize(area, triangles, hi, options).Bytes() > budget)
    return std::numeric_limits<double>::infinity();
  for (int n = 0; n < 100; ++n) {
    const double mid = 0.5 * (lo + hi);
    (ModelSize(area, triangles, mid, options).Bytes() > budget ? lo : hi) = mid;
  }
  return hi;
}

/// Throws VoxelizeError when the modelled size exceeds a non-zero budget.
void CheckBudget(double area, double triangles, const VoxelizeOptions& options,
                 std::size_t estimate) {
  if (options.memory_budget_bytes == 0 || estimate <= options.memory_budget_bytes) return;
  const double fit = SmallestFittingVoxelSize(area, triangles, options,
                                              static_cast<double>(options.memory_budget_bytes));
  std::ostringstream msg;
  msg << "voxelization at voxel size " << options.voxel_size_mm << " mm needs about " << estimate
      << " bytes, over the memory budget of " << options.memory_budget_bytes << " bytes; ";
  if (std::isfinite(fit)) {
    msg << "the smallest voxel size that fits is about " << RoundUp(fit) << " mm";
  } else {
    msg << "no voxel size fits (the triangle count alone exceeds it)";
  }
  throw VoxelizeError(msg.str());
}

std::size_t ToBytes(const SizeModel& m) {
  return static_cast<std::size_t>(std::min(m.Bytes(), 1e18));
}

}  // namespace

Eigen::Vector3i VoxelGrid::VoxelOf(const Eigen::Vector3d& p_F) const {
  // floor((p - origin) / s), then nudged so that |p - centre| <= s / 2 holds as
  // evaluated in double, the same arithmetic as the exact triangle/box test on
  // VoxelCenter: a point on a voxel face then always lands in a voxel whose
  // closed cube the test says contains it.
  const double half = 0.5 * voxel_size_mm;
  Eigen::Vector3i ijk;
  for (int a = 0; a < 3; ++a) {
    const double x = (p_F[a] - origin_F[a]) / voxel_size_mm;
    double q = std::abs(x) < 1e9 ? detail::FloorInt(x) : std::floor(x);  // the same value
    if (!(std::abs(q) < 2147483647.0)) {  // NaN, empty grid (size 0) or far away
      ijk[a] = std::isnan(q) ? -1 : (q > 0 ? 2147483647 : -2147483647);
      continue;
    }
    auto center = [&](double i) { return origin_F[a] + voxel_size_mm * (i + 0.5); };
    if (p_F[a] - center(q) > half) q += 1.0;
    if (p_F[a] - center(q) < -half) q -= 1.0;
    ijk[a] = static_cast<int>(q);
  }
  return ijk;
}

VoxelClass VoxelGrid::Classify(const Eigen::Vector3i& ijk) const {
  if ((ijk.array() < 0).any() || (ijk.array() >= dims.array()).any()) {
    return VoxelClass::kUndefined;
  }
  const std::uint64_t key = MortonEncode(ijk);
  if (std::binary_search(surface_keys.begin(), surface_keys.end(), key)) {
    return VoxelClass::kSurface;
  }
  if (std::binary_search(proximity_keys.begin(), proximity_keys.end(), key)) {
    return VoxelClass::kProximity;
  }
  if (detail::RunsContain(interior_runs, ijk.x(), ijk.y(), ijk.z())) return VoxelClass::kInterior;
  return VoxelClass::kUndefined;
}

bool VoxelGrid::IsInterior(const Eigen::Vector3i& ijk) const {
  if ((ijk.array() < 0).any() || (ijk.array() >= dims.array()).any()) return false;
  return detail::RunsContain(interior_runs, ijk.x(), ijk.y(), ijk.z());
}

std::size_t VoxelGrid::MemoryBytes() const {
  return surface_keys.capacity() * sizeof(std::uint64_t) +
         triangle_offsets.capacity() * sizeof(std::uint32_t) +
         triangle_indices.capacity() * sizeof(std::uint32_t) +
         proximity_keys.capacity() * sizeof(std::uint64_t) +
         interior_runs.capacity() * sizeof(VoxelRun);
}

std::size_t EstimateVoxelizeBytes(const io::TriangleMesh& mesh, const VoxelizeOptions& options) {
  CheckOptions(options);
  return ToBytes(ModelSize(mesh.SurfaceArea(), static_cast<double>(mesh.num_triangles()),
                           options.voxel_size_mm, options));
}

VoxelGrid Voxelize(const io::TriangleMesh& mesh, const VoxelizeOptions& options,
                   VoxelizeStats* stats) {
  CheckOptions(options);
  CheckMesh(mesh);
  VoxelizeStats local_stats;
  VoxelizeStats& st = stats ? *stats : local_stats;
  st = VoxelizeStats{};
  VoxelGrid grid;
  grid.voxel_size_mm = options.voxel_size_mm;
  if (mesh.empty()) return grid;

  const detail::GridFrame frame = MakeFrame(mesh.Bounds(), options);
  const double area = mesh.SurfaceArea();
  const auto triangles = static_cast<double>(mesh.num_triangles());
  const SizeModel model = ModelSize(area, triangles, options.voxel_size_mm, options);
  CheckBudget(area, triangles, options, ToBytes(model));
  grid.origin_F = frame.origin;
  grid.dims = frame.dims;

  auto start = std::chrono::steady_clock::now();
  detail::BuildSurface(mesh, frame, static_cast<std::size_t>(1.25 * model.pairs), &grid, &st);
  st.seconds_surface = detail::SecondsSince(start);
  if (options.classify_proximity) {
    start = std::chrono::steady_clock::now();
    detail::BuildProximity(mesh, frame, options.proximity_layers, &grid);
    st.seconds_proximity = detail::SecondsSince(start);
  }
  if (options.classify_interior) {
    start = std::chrono::steady_clock::now();
    detail::BuildInterior(mesh, frame, &grid, &st);
    st.seconds_interior = detail::SecondsSince(start);
  }
  st.surface_voxels = grid.surface_keys.size();
  st.proximity_voxels = grid.proximity_keys.size();
  for (const VoxelRun& r : grid.interior_runs) {
    st.interior_voxels += static_cast<std::size_t>(r.x_end - r.x_begin);
  }
  return grid;
}

}  // namespace occlude::collision
