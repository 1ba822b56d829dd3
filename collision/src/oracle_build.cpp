// JawOracle construction: both sphere trees, the lower jaw's narrow-band
// distance field, the upper's area-weighted surface samples grouped by voxel,
// and the arch frame.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "occlude/collision/morton.h"
#include "occlude/collision/oracle.h"
#include "voxelize_detail.h"

namespace occlude::collision {
namespace {

// Index of the surface voxel containing p (a point on triangle t), or -1.
long FindSampleVoxel(const VoxelGrid& grid, const Eigen::Vector3d& p, std::uint32_t t) {
  const Eigen::Vector3i base = grid.VoxelOf(p);
  for (int n = 0; n < 27; ++n) {  // own voxel first, then neighbours (rounding at faces)
    const int k = n == 0 ? 13 : (n <= 13 ? n - 1 : n);
    const Eigen::Vector3i v = base + Eigen::Vector3i(k % 3 - 1, (k / 3) % 3 - 1, k / 9 - 1);
    if ((v.array() < 0).any() || (v.array() >= grid.dims.array()).any()) continue;
    const auto it =
        std::lower_bound(grid.surface_keys.begin(), grid.surface_keys.end(), MortonEncode(v));
    if (it == grid.surface_keys.end() || *it != MortonEncode(v)) continue;
    const auto idx = static_cast<std::size_t>(it - grid.surface_keys.begin());
    for (auto i = grid.triangles_begin(idx); i < grid.triangles_end(idx); ++i) {
      if (grid.triangle_indices[i] == t) return static_cast<long>(idx);
    }
  }
  return -1;
}

struct RawSample {
  Eigen::Vector3d p;
  double area;
  std::uint32_t triangle;
};

// Splits triangle t into k^2 congruent pieces (k from the spacing) and returns
// their centroids, each standing for area/k^2.
void SampleTriangle(const io::TriangleMesh& m, std::uint32_t t, double spacing,
                    std::vector<RawSample>* out) {
  const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const int k = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
  const double area = 0.5 * (b - a).cross(c - a).norm() / (k * k);
  const Eigen::Vector3d u = (b - a) / k, v = (c - a) / k;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; i + j < k; ++j) {
      const Eigen::Vector3d o = a + i * u + j * v;
      out->push_back({o + (u + v) / 3.0, area, t});
      if (i + j < k - 1) out->push_back({o + 2.0 * (u + v) / 3.0, area, t});
    }
  }
}

// Merges the samples of small triangles so that the surface is sampled at
// about `spacing` wherever its triangles are finer than that: each upper voxel
// is split into k^3 sub-cells (k = ceil(voxel / spacing), so a sub-cell's edge
// is at most the spacing), and the samples of one part in one sub-cell become
// one: the member nearest their area-weighted centroid (a point of the
// surface, not a point between curved patches), carrying their total area.
// Samples outside every voxel (voxel_of < 0) are dropped as before. Output in
// (voxel, part, sub-cell) order; deterministic (ties keep the first member).
void MergeSamples(const VoxelGrid& grid, const io::TriangleMesh& mesh, double spacing,
                  std::vector<RawSample>* raw, std::vector<long>* voxel_of) {
  const double s = grid.voxel_size_mm;
  const int k = std::max(1, static_cast<int>(std::ceil(s / spacing - 1e-9)));
  struct Keyed {
    long voxel;
    std::int32_t part;
    std::int64_t sub;
    std::uint32_t index;
  };
  std::vector<Keyed> keyed;
  keyed.reserve(raw->size());
  for (std::size_t i = 0; i < raw->size(); ++i) {
    const long v = (*voxel_of)[i];
    if (v < 0) continue;
    const Eigen::Vector3d corner =
        grid.origin_F +
        s * MortonDecode(grid.surface_keys[static_cast<std::size_t>(v)]).cast<double>();
    std::int64_t sub = 0;
    for (int a = 3; a-- > 0;) {
      const double u = ((*raw)[i].p[a] - corner[a]) / s * k;
      sub = sub * k + std::clamp(static_cast<std::int64_t>(std::floor(u)), std::int64_t{0},
                                 std::int64_t{k - 1});
    }
    const std::uint32_t t = (*raw)[i].triangle;
    keyed.push_back({v, mesh.triangle_part.empty() ? 0 : mesh.triangle_part[t], sub,
                     static_cast<std::uint32_t>(i)});
  }
  std::sort(keyed.begin(), keyed.end(), [](const Keyed& a, const Keyed& b) {
    return std::tie(a.voxel, a.part, a.sub, a.index) < std::tie(b.voxel, b.part, b.sub, b.index);
  });
  std::vector<RawSample> merged;
  std::vector<long> merged_voxel;
  for (std::size_t first = 0; first < keyed.size();) {
    std::size_t last = first + 1;
    while (last < keyed.size() && keyed[last].voxel == keyed[first].voxel &&
           keyed[last].part == keyed[first].part && keyed[last].sub == keyed[first].sub) {
      ++last;
    }
    Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
    double area = 0.0;
    for (std::size_t j = first; j < last; ++j) {
      const RawSample& r = (*raw)[keyed[j].index];
      weighted += r.area * r.p;
      area += r.area;
    }
    const Eigen::Vector3d centroid =
        area > 0.0 ? Eigen::Vector3d(weighted / area) : (*raw)[keyed[first].index].p;
    std::uint32_t best = keyed[first].index;
    for (std::size_t j = first + 1; j < last; ++j) {
      const std::uint32_t i = keyed[j].index;
      if (((*raw)[i].p - centroid).squaredNorm() < ((*raw)[best].p - centroid).squaredNorm())
        best = i;
    }
    RawSample r = (*raw)[best];
    r.area = area;
    merged.push_back(r);
    merged_voxel.push_back(keyed[first].voxel);
    first = last;
  }
  raw->swap(merged);
  voxel_of->swap(merged_voxel);
}

// Centre of the bounding box of points [first, last) (not empty).
Eigen::Vector3f BoxCentre(const std::vector<Eigen::Vector3f>& p, std::size_t first,
                          std::size_t last) {
  Eigen::Vector3d lo = p[first].cast<double>(), hi = lo;
  for (auto i = first; i < last; ++i) {
    lo = lo.cwiseMin(p[i].cast<double>());
    hi = hi.cwiseMax(p[i].cast<double>());
  }
  return (0.5 * (lo + hi)).cast<float>();
}

// Largest distance of offsets [first, last) from o, rounded up so that float
// storage never shrinks it.
float Radius(const std::vector<Eigen::Vector4f>& offsets, std::size_t first, std::size_t last,
             const Eigen::Vector3f& o) {
  double radius = 0.0;
  for (auto i = first; i < last; ++i) {
    radius = std::max(radius, (offsets[i].head<3>().cast<double>() - o.cast<double>()).norm());
  }
  return static_cast<float>(radius * (1.0 + 1e-6) + 1e-6);
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
  if (std::isnan(options.field_bound_mm) || !(options.field_bound_depth_mm >= 0.0) ||
      !std::isfinite(options.field_bound_depth_mm)) {
    throw std::invalid_argument(
        "OracleOptions.field_bound_mm must not be NaN (negative: no field bound) and "
        "field_bound_depth_mm must be "
        "finite and >= 0");
  }
  const auto start = std::chrono::steady_clock::now();
  SphereTreeOptions tree_options;
  tree_options.voxelize.voxel_size_mm = options.voxel_size_mm;
  {
    // The two trees are independent: the upper's on a second thread (a build
    // may use two), an exception there rethrown here.
    std::exception_ptr upper_error;
    std::thread upper_thread([&] {
      try {
        upper_ = SphereTree::Build(upper_U, tree_options);
      } catch (...) {
        upper_error = std::current_exception();
      }
    });
    try {
      lower_ = SphereTree::Build(lower_L, tree_options);
    } catch (...) {
      upper_thread.join();
      throw;
    }
    upper_thread.join();
    if (upper_error) std::rethrow_exception(upper_error);
  }
  NarrowBandOptions sdf_options;
  sdf_options.dilation_voxels = options.sdf_dilation_voxels;
  sdf_ = NarrowBandSdf::Build(lower_L, lower_.grid(), sdf_options);
  if (options.field_bound_mm >= 0.0) {
    // Widened by a margin far above float rounding in the trilinear values (a
    // rounded value may fall an ulp outside its voxel's corner range).
    constexpr double kMarginMm = 1e-5;
    // Cells of voxel / split (see FieldBoundSplit); with half-voxel cells,
    // levels 0, 1, 2 and 4 of the bound keep its coarsest cap as far out (in
    // mm) as the default levels 0, 1 and 3 of whole voxels.
    const int split = FieldBoundSplit(options.voxel_size_mm);
    field_bound_ = DistanceBound::Build(
        sdf_.BandCellsWithin(static_cast<float>(options.field_bound_depth_mm + kMarginMm),
                             static_cast<float>(options.field_bound_mm + kMarginMm), split),
        DistanceBound::kMaxVoxels,
        split == 2 ? std::vector<int>{0, 1, 2, 4} : std::vector<int>{0, 1, 3});
  }
  arch_ = options.arch ? *options.arch : EstimateArchFrame(*lower_L, *upper_U);

  // Samples of the upper surface, grouped by voxel (counting sort).
  const io::TriangleMesh& up = *upper_U;
  const VoxelGrid& grid = upper_.grid();
  const double spacing = options.sample_spacing_mm > 0 ? options.sample_spacing_mm : 0.3;
  std::vector<RawSample> raw;
  std::vector<long> voxel_of;
  for (std::uint32_t t = 0; t < up.num_triangles(); ++t) {
    const std::size_t first = raw.size();
    SampleTriangle(up, t, spacing, &raw);
    for (std::size_t i = first; i < raw.size(); ++i)
      voxel_of.push_back(FindSampleVoxel(grid, raw[i].p, t));
  }
  MergeSamples(grid, up, spacing, &raw, &voxel_of);
  const std::size_t nv = grid.num_surface();
  voxel_sample_begin_.assign(nv + 1, 0);
  for (const long v : voxel_of) {
    if (v >= 0) ++voxel_sample_begin_[static_cast<std::size_t>(v) + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) voxel_sample_begin_[v + 1] += voxel_sample_begin_[v];
  const std::size_t ns = voxel_sample_begin_[nv];
  sample_p_U_.resize(ns);
  sample_area_.resize(ns);
  sample_part_.resize(ns);
  std::vector<std::uint32_t> fill(voxel_sample_begin_.begin(), voxel_sample_begin_.end() - 1);
  // One representative sample per connected component of the upper surface,
  // with the component's sample count (CountNestedPieces).
  const std::vector<std::int32_t> component = detail::ComponentOfTriangle(up);
  std::vector<std::uint32_t> component_slot;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (voxel_of[i] < 0) continue;
    const std::uint32_t slot = fill[static_cast<std::size_t>(voxel_of[i])]++;
    sample_p_U_[slot] = raw[i].p.cast<float>();
    sample_area_[slot] = static_cast<float>(raw[i].area);
    sample_part_[slot] = up.triangle_part.empty() ? 0 : up.triangle_part[raw[i].triangle];
    const auto c = static_cast<std::uint32_t>(component[raw[i].triangle]);
    if (c >= component_slot.size()) component_slot.resize(c + 1, ~0u);
    if (component_slot[c] == ~0u) {
      component_slot[c] = static_cast<std::uint32_t>(component_samples_.size());
      component_samples_.push_back({slot, 0});
    }
    ++component_samples_[component_slot[c]].count;
  }
  // Voxel-level samples: area-weighted centroid and the dominant part.
  voxel_centroid_U_.resize(nv);
  voxel_area_.resize(nv);
  voxel_part_.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    double area = 0.0;
    for (auto i = voxel_sample_begin_[v]; i < voxel_sample_begin_[v + 1]; ++i) {
      c += static_cast<double>(sample_area_[i]) * sample_p_U_[i].cast<double>();
      area += static_cast<double>(sample_area_[i]);
    }
    voxel_centroid_U_[v] =
        (area > 0 ? Eigen::Vector3d(c / area)
                  : upper_.grid().VoxelCenter(MortonDecode(grid.surface_keys[v])))
            .cast<float>();
    voxel_area_[v] = static_cast<float>(area);
    voxel_part_[v] = voxel_sample_begin_[v] < voxel_sample_begin_[v + 1]
                         ? sample_part_[voxel_sample_begin_[v]]
                         : 0;
  }
  // Leaf ranges per upper octree node (children are contiguous, in order).
  const Octree& oct = upper_.octree();
  node_leaf_begin_.assign(oct.num_nodes(), 0);
  node_leaf_end_.assign(oct.num_nodes(), 0);
  for (std::size_t n = oct.num_nodes(); n-- > 0;) {
    if (n >= oct.leaf_begin()) {
      node_leaf_begin_[n] = static_cast<std::uint32_t>(n - oct.leaf_begin());
      node_leaf_end_[n] = node_leaf_begin_[n] + 1;
    } else {
      const std::uint32_t first = oct.first_child[n];
      const auto count = static_cast<std::uint32_t>(__builtin_popcount(oct.child_mask[n]));
      node_leaf_begin_[n] = node_leaf_begin_[first];
      node_leaf_end_[n] = node_leaf_end_[first + count - 1];
    }
  }
  // Per cell (node of the query's cell level) and per voxel: the centre of
  // the samples' bounding box and their largest distance from it (the query's
  // culls). Samples and voxel centres are also stored as float offsets from
  // their cell's centre, the radii measured from those offsets.
  {
    const int level = std::min(options_.cell_level, oct.top_level);
    const std::uint32_t begin = oct.level_begin[static_cast<std::size_t>(level)];
    const std::uint32_t end = oct.level_end[static_cast<std::size_t>(level)];
    cell_center_U_.assign(end - begin, Eigen::Vector3f::Zero());
    cell_radius_.assign(end - begin, 0.0f);
    sample_offset_U_.assign(sample_p_U_.size(), Eigen::Vector4f::Zero());
    voxel_sphere_U_.assign(nv, Eigen::Vector4f::Zero());
    for (std::uint32_t n = begin; n < end; ++n) {
      const auto first = voxel_sample_begin_[node_leaf_begin_[n]],
                 last = voxel_sample_begin_[node_leaf_end_[n]];
      if (first == last) continue;
      const Eigen::Vector3f c = BoxCentre(sample_p_U_, first, last);
      for (auto i = first; i < last; ++i) {
        sample_offset_U_[i].head<3>() =
            (sample_p_U_[i].cast<double>() - c.cast<double>()).cast<float>();
      }
      cell_center_U_[n - begin] = c;
      cell_radius_[n - begin] = Radius(sample_offset_U_, first, last, Eigen::Vector3f::Zero());
      for (auto v = node_leaf_begin_[n]; v < node_leaf_end_[n]; ++v) {
        const auto vb = voxel_sample_begin_[v], ve = voxel_sample_begin_[v + 1];
        if (vb == ve) continue;
        const Eigen::Vector3f o =
            (BoxCentre(sample_p_U_, vb, ve).cast<double>() - c.cast<double>()).cast<float>();
        voxel_sphere_U_[v] =
            Eigen::Vector4f(o.x(), o.y(), o.z(), Radius(sample_offset_U_, vb, ve, o));
      }
    }
  }
  // Per node at or above the cell level: its samples' bounding sphere, the
  // broad phase's spheres (CellRequest::b_spheres); radius -1 without samples.
  if (!oct.empty()) {
    const std::uint32_t end =
        oct.level_end[static_cast<std::size_t>(std::min(options_.cell_level, oct.top_level))];
    node_sample_sphere_U_.assign(end, Eigen::Vector4f(0.0f, 0.0f, 0.0f, -1.0f));
    for (std::uint32_t n = 0; n < end; ++n) {
      const auto first = voxel_sample_begin_[node_leaf_begin_[n]],
                 last = voxel_sample_begin_[node_leaf_end_[n]];
      if (first == last) continue;
      const Eigen::Vector3f c = BoxCentre(sample_p_U_, first, last);
      double radius = 0.0;
      for (auto i = first; i < last; ++i)
        radius = std::max(radius, (sample_p_U_[i] - c).cast<double>().norm());
      node_sample_sphere_U_[n] =
          Eigen::Vector4f(c.x(), c.y(), c.z(), static_cast<float>(radius * (1.0 + 1e-6) + 1e-6));
    }
  }
  // The samples' bounding sphere (box centre, farthest sample), for CountNestedPieces.
  if (!sample_p_U_.empty()) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
                    hi = -lo;
    for (const Eigen::Vector3f& p : sample_p_U_) {
      lo = lo.cwiseMin(p.cast<double>());
      hi = hi.cwiseMax(p.cast<double>());
    }
    samples_centre_U_ = 0.5 * (lo + hi);
    for (const Eigen::Vector3f& p : sample_p_U_) {
      samples_radius_ = std::max(samples_radius_, (p.cast<double>() - samples_centre_U_).norm());
    }
    samples_radius_ += 1e-6;  // float storage of the samples
  }
  // Row index of the lower's interior runs (sorted by z, then y).
  const VoxelGrid& lower_grid = lower_.grid();
  if (!lower_grid.interior_runs.empty()) {
    const auto ny = static_cast<std::size_t>(lower_grid.dims.y());
    interior_row_begin_.assign(ny * static_cast<std::size_t>(lower_grid.dims.z()) + 1, 0);
    for (const VoxelRun& r : lower_grid.interior_runs) {
      ++interior_row_begin_[static_cast<std::size_t>(r.y) + ny * static_cast<std::size_t>(r.z) + 1];
    }
    for (std::size_t i = 0; i + 1 < interior_row_begin_.size(); ++i)
      interior_row_begin_[i + 1] += interior_row_begin_[i];
  }
  // Anterior teeth by Universal number: 6..11 (upper), 22..27 (lower).
  for (const auto& part : up.parts) {
    const int t = part.tooth_number;
    part_has_tooth_.push_back(t > 0);
    part_is_anterior_tooth_.push_back((t >= 6 && t <= 11) || (t >= 22 && t <= 27));
  }
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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
