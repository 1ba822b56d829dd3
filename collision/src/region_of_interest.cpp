// The region of interest of a jaw pair (see region_of_interest.h for the reach, the selection
// and the open-border contract): the other jaw's distance bound, one probe per triangle, and
// the sub-meshes with their maps back to the whole meshes.
#include "occlude/collision/region_of_interest.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "occlude/angles.h"
#include "occlude/collision/distance_bound.h"
#include "occlude/collision/voxel_grid.h"
#include "parallel.h"
#include "region_code_hash.h"
#include "voxelize_detail.h"

namespace occlude::collision {
namespace {

constexpr double kSqrt3 = 1.7320508075688772;
/// Levels of the selection's distance bound: voxels up to cells of 16 voxels, so that with
/// 0.5 mm voxels the bound certifies up to 60 mm (7.5 cells of 8 mm).
const std::vector<int> kBoundLevels = {0, 1, 2, 3, 4};

void Validate(const RegionOfInterestRequest& r) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("RegionOfInterestRequest." + what);
  };
  if (!r.X_LU_start.matrix().allFinite()) fail("X_LU_start: must be finite");
  if (!r.pivot_L.allFinite()) fail("pivot_L: must be finite");
  for (int d = 0; d < 6; ++d) {
    const auto i = static_cast<std::size_t>(d);
    if (!std::isfinite(r.bound_min[i]) || !std::isfinite(r.bound_max[i]) ||
        r.bound_min[i] > r.bound_max[i]) {
      fail("bound_min/bound_max[" + std::to_string(d) + "]: must be finite with min <= max");
    }
  }
  if (!(std::isfinite(r.band_mm) && r.band_mm >= 0.0)) fail("band_mm: must be finite and >= 0");
  if (!(std::isfinite(r.voxel_size_mm) && r.voxel_size_mm > 0.0))
    fail("voxel_size_mm: must be > 0");
}

// Norm of the largest magnitudes of the free DOFs [first, first + 3).
double BoundNorm(const RegionOfInterestRequest& r, int first) {
  double sum = 0.0;
  for (int d = first; d < first + 3; ++d) {
    const auto i = static_cast<std::size_t>(d);
    if (r.locked[i]) continue;
    const double m = std::max(std::abs(r.bound_min[i]), std::abs(r.bound_max[i]));
    sum += m * m;
  }
  return std::sqrt(sum);
}

// The distance bound of `mesh_L`'s surface voxels (its voxel cubes hold the surface).
DistanceBound BoundOf(const io::TriangleMesh& mesh_L, double voxel_mm) {
  VoxelizeOptions options;
  options.voxel_size_mm = voxel_mm;
  options.classify_proximity = false;
  options.classify_interior = false;
  return DistanceBound::Build(Voxelize(mesh_L, options), DistanceBound::kMaxVoxels, kBoundLevels);
}

// True unless the bound proves every point of triangle (a, b, c) farther than `reach` from
// its surface: each piece is within its bounding-sphere radius of the sphere's centre, so a
// piece excluded there within reach + radius is farther than reach from every voxel cube.
bool WithinReach(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                 const DistanceBound& other, double reach) {
  const Eigen::Vector3d centre = 0.5 * (a.cwiseMin(b).cwiseMin(c) + a.cwiseMax(b).cwiseMax(c));
  const double radius = std::max({(a - centre).norm(), (b - centre).norm(), (c - centre).norm()});
  return !other.Excludes(centre, reach + radius);
}

// Triangles of `mesh_L` not proved farther than `reach` from the bound's surface. A long
// triangle is tested in k^2 congruent pieces of edges up to about two of the bound's cells, so
// that its size does not blunt the test (a wall or a palate spanning centimetres).
std::vector<std::uint32_t> Kept(const io::TriangleMesh& mesh_L, const DistanceBound& other,
                                double reach) {
  const double piece = 2.0 * other.cell_mm();
  std::vector<std::uint32_t> kept;
  for (std::uint32_t t = 0; t < mesh_L.num_triangles(); ++t) {
    const Eigen::Vector3d &a = mesh_L.corner(t, 0), &b = mesh_L.corner(t, 1),
                          &c = mesh_L.corner(t, 2);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int k =
        piece > 0.0 ? std::clamp(static_cast<int>(std::ceil(longest / piece)), 1, 256) : 1;
    const Eigen::Vector3d u = (b - a) / k, v = (c - a) / k;
    bool near = false;
    for (int i = 0; i < k && !near; ++i) {
      for (int j = 0; i + j < k && !near; ++j) {
        const Eigen::Vector3d o = a + i * u + j * v;
        near = WithinReach(o, o + u, o + v, other, reach) ||
               (i + j < k - 1 && WithinReach(o + u, o + u + v, o + v, other, reach));
      }
    }
    if (near) kept.push_back(t);
  }
  return kept;
}

// `kept` (ascending) grown by every closed component of `mesh` it touches: cutting one would
// open it and lose its interior (the oracle's deep samples and its culls of cells inside).
// `closed`: detail::ClosedComponentOfTriangle of the mesh.
std::vector<std::uint32_t> WholeClosedComponents(const io::TriangleMesh& mesh,
                                                 const std::vector<std::int32_t>& closed,
                                                 const std::vector<std::uint32_t>& kept) {
  std::vector<bool> touched;
  for (const std::uint32_t t : kept) {
    const std::int32_t c = closed[t];
    if (c < 0) continue;
    if (touched.size() <= static_cast<std::size_t>(c))
      touched.resize(static_cast<std::size_t>(c) + 1, false);
    touched[static_cast<std::size_t>(c)] = true;
  }
  std::vector<std::uint32_t> grown;
  grown.reserve(kept.size());
  std::size_t k = 0;
  for (std::uint32_t t = 0; t < mesh.num_triangles(); ++t) {
    const bool listed = k < kept.size() && kept[k] == t;
    if (listed) ++k;
    const std::int32_t c = closed[t];
    if (listed || (c >= 0 && static_cast<std::size_t>(c) < touched.size() &&
                   touched[static_cast<std::size_t>(c)])) {
      grown.push_back(t);
    }
  }
  return grown;
}

RegionMesh SubMesh(const std::shared_ptr<const io::TriangleMesh>& whole,
                   std::vector<std::uint32_t> kept) {
  RegionMesh out;
  if (kept.size() == whole->num_triangles()) {  // nothing cut: share the whole mesh
    out.mesh = whole;
    out.original_triangle = std::move(kept);
    return out;
  }
  auto sub = std::make_shared<io::TriangleMesh>();
  sub->parts = whole->parts;
  std::vector<std::int32_t> new_index(whole->num_vertices(), -1);
  sub->triangles.reserve(kept.size());
  for (const std::uint32_t t : kept) {
    Eigen::Vector3i tri;
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(whole->triangles[t][k]);
      if (new_index[v] < 0) {
        new_index[v] = static_cast<std::int32_t>(sub->vertices.size());
        sub->vertices.push_back(whole->vertices[v]);
      }
      tri[k] = new_index[v];
    }
    sub->triangles.push_back(tri);
    if (whole->face_normals.size() == whole->num_triangles())
      sub->face_normals.push_back(whole->face_normals[t]);
    if (whole->triangle_part.size() == whole->num_triangles())
      sub->triangle_part.push_back(whole->triangle_part[t]);
  }
  // The whole mesh's extreme vertices along each axis, unused when not already kept: Voxelize
  // frames its grid by the vertices' bounds, so the sub-mesh's grids are the whole mesh's (same
  // origin and dims, hence the same voxel keys, octree cells and sample order for the kept
  // triangles). Real vertices rather than box corners, so that a maximum of a linear function
  // over the vertices (the planner's lowest cusp) is not moved by them.
  if (!kept.empty()) {
    for (int axis = 0; axis < 3; ++axis) {
      std::size_t lo = 0, hi = 0;
      for (std::size_t v = 0; v < whole->num_vertices(); ++v) {
        if (whole->vertices[v][axis] < whole->vertices[lo][axis]) lo = v;
        if (whole->vertices[v][axis] > whole->vertices[hi][axis]) hi = v;
      }
      for (const std::size_t v : {lo, hi}) {
        if (new_index[v] < 0) {
          new_index[v] = static_cast<std::int32_t>(sub->vertices.size());
          sub->vertices.push_back(whole->vertices[v]);
        }
      }
    }
  }
  for (auto* v : {&sub->vertices, &sub->face_normals})
    v->shrink_to_fit();  // trees count mesh bytes
  sub->triangles.shrink_to_fit();
  sub->triangle_part.shrink_to_fit();
  out.mesh = std::move(sub);
  out.original_triangle = std::move(kept);
  return out;
}

}  // namespace

double MaxDisplacementMm(const io::TriangleMesh& upper_U, const RegionOfInterestRequest& request) {
  Validate(request);
  double radius = 0.0;  // farthest upper vertex from the pivot at the start pose
  for (const Eigen::Vector3d& v : upper_U.vertices) {
    radius = std::max(radius, (request.X_LU_start * v - request.pivot_L).norm());
  }
  const double angle = std::min(BoundNorm(request, 3) * kPi / 180.0, kPi);
  return BoundNorm(request, 0) + 2.0 * std::sin(0.5 * angle) * radius;
}

struct RegionSelector::Impl {
  std::shared_ptr<const io::TriangleMesh> lower_L, upper_U;
  RegionOfInterestRequest request;
  double displacement_mm = 0.0;
  io::TriangleMesh upper_L;                               ///< the upper at the start pose
  std::optional<DistanceBound> upper_bound, lower_bound;  ///< set unless a jaw is empty
  std::vector<std::int32_t> lower_closed;  ///< detail::ClosedComponentOfTriangle of the lower
  double seconds = 0.0;                    ///< of the construction
};

RegionSelector::RegionSelector(std::shared_ptr<const io::TriangleMesh> lower_L,
                               std::shared_ptr<const io::TriangleMesh> upper_U,
                               const RegionOfInterestRequest& request)
    : impl_(std::make_unique<Impl>()) {
  if (!lower_L || !upper_U) throw std::invalid_argument("ComputeRegionOfInterest: null mesh");
  const auto start = std::chrono::steady_clock::now();
  Impl& m = *impl_;
  m.displacement_mm = MaxDisplacementMm(*upper_U, request);  // validates the request
  m.upper_L = upper_U->Transformed(request.X_LU_start);
  if (!lower_L->empty() && !m.upper_L.empty()) {
    // Three independent pieces, each on a core of its own.
    detail::RunConcurrently(
        detail::ResolveThreads(0),
        {[&] { m.upper_bound = BoundOf(m.upper_L, request.voxel_size_mm); },
         [&] { m.lower_bound = BoundOf(*lower_L, request.voxel_size_mm); },
         [&] { m.lower_closed = detail::ClosedComponentOfTriangle(*lower_L); }});
  }
  m.lower_L = std::move(lower_L);
  m.upper_U = std::move(upper_U);
  m.request = request;
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

RegionSelector::~RegionSelector() = default;
RegionSelector::RegionSelector(RegionSelector&&) noexcept = default;
RegionSelector& RegionSelector::operator=(RegionSelector&&) noexcept = default;

double RegionSelector::seconds() const { return impl_->seconds; }

RegionOfInterest RegionSelector::Select(double band_mm) const {
  const Impl& m = *impl_;
  RegionOfInterestRequest banded = m.request;
  banded.band_mm = band_mm;
  Validate(banded);
  const auto start = std::chrono::steady_clock::now();
  RegionOfInterest roi;
  RegionOfInterestStats& s = roi.stats;
  s.band_mm = band_mm;
  s.displacement_mm = m.displacement_mm;
  s.reach_mm = s.band_mm + s.displacement_mm;
  s.lower_total = m.lower_L->num_triangles();
  s.upper_total = m.upper_U->num_triangles();
  // The two jaws' selections are independent: one on each core.
  detail::RunConcurrently(detail::ResolveThreads(0),
                          {[&] {
                             std::vector<std::uint32_t> kept;
                             if (m.upper_bound && m.lower_bound) {
                               kept = WholeClosedComponents(
                                   *m.lower_L, m.lower_closed,
                                   Kept(*m.lower_L, *m.upper_bound, s.reach_mm));
                             }
                             s.lower_kept = kept.size();
                             roi.lower = SubMesh(m.lower_L, std::move(kept));
                           },
                           [&] {
                             std::vector<std::uint32_t> kept;
                             if (m.upper_bound && m.lower_bound)
                               kept = Kept(m.upper_L, *m.lower_bound, s.reach_mm);
                             s.upper_kept = kept.size();
                             roi.upper = SubMesh(m.upper_U, std::move(kept));
                           }});
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return roi;
}

RegionOfInterest ComputeRegionOfInterest(const std::shared_ptr<const io::TriangleMesh>& lower_L,
                                         const std::shared_ptr<const io::TriangleMesh>& upper_U,
                                         const RegionOfInterestRequest& request) {
  const RegionSelector selector(lower_L, upper_U, request);
  RegionOfInterest roi = selector.Select(request.band_mm);
  roi.stats.seconds += selector.seconds();
  return roi;
}

const char* RegionSelectionCodeVersion() { return kRegionCodeHash; }

RegionOfInterest RegionOfKept(const std::shared_ptr<const io::TriangleMesh>& lower_L,
                              const std::shared_ptr<const io::TriangleMesh>& upper_U,
                              std::vector<std::uint32_t> lower_kept,
                              std::vector<std::uint32_t> upper_kept,
                              const RegionOfInterestStats& stats) {
  if (!lower_L || !upper_U) throw std::invalid_argument("RegionOfKept: null mesh");
  auto check = [](const std::vector<std::uint32_t>& kept, const io::TriangleMesh& mesh,
                  const char* jaw) {
    for (std::size_t i = 0; i < kept.size(); ++i) {
      if (kept[i] >= mesh.num_triangles() || (i > 0 && kept[i] <= kept[i - 1])) {
        throw std::invalid_argument(std::string("RegionOfKept: the ") + jaw +
                                    "'s kept triangles are not increasing indices of its mesh");
      }
    }
  };
  check(lower_kept, *lower_L, "lower");
  check(upper_kept, *upper_U, "upper");
  RegionOfInterest roi;
  roi.stats = stats;
  roi.stats.lower_kept = lower_kept.size();
  roi.stats.upper_kept = upper_kept.size();
  roi.stats.lower_total = lower_L->num_triangles();
  roi.stats.upper_total = upper_U->num_triangles();
  roi.lower = SubMesh(lower_L, std::move(lower_kept));
  roi.upper = SubMesh(upper_U, std::move(upper_kept));
  return roi;
}

double OracleReadRadiusMm(const OracleOptions& options, double exact_reach_mm) {
  const double s = options.voxel_size_mm;
  const double k = std::max(0, options.sdf_dilation_voxels);
  const double exact = std::ceil(std::max(0.0, exact_reach_mm) / s) + 2.0;
  return kSqrt3 * s * std::max(k + 3.0, exact);
}

bool RegionCoversPose(const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU_start,
                      const Eigen::Isometry3d& X_LU, double displacement_mm) {
  if (!X_LU.matrix().allFinite()) return false;
  for (const Eigen::Vector3d& v : upper_U.vertices) {
    if (!((X_LU * v - X_LU_start * v).norm() <= displacement_mm)) return false;
  }
  return true;
}

}  // namespace occlude::collision
