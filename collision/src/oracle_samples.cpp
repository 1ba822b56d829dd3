// JawOracle construction, the upper jaw's side: its sphere tree, its area-weighted surface
// samples grouped by voxel (split to the spacing, then merged where the triangles are finer),
// the voxel-level samples, and the spheres of the cells and nodes that the query culls with.
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "occlude/assert.h"
#include "occlude/collision/morton.h"
#include "occlude/collision/oracle.h"
#include "oracle_trees.h"
#include "parallel.h"
#include "voxelize_detail.h"

namespace occlude::collision {
namespace {

struct RawSample {
  Eigen::Vector3d p;
  double area;
  std::uint32_t triangle;
};

// Samples with the surface voxel holding each (-1: none).
struct RawSamples {
  std::vector<RawSample> samples;
  std::vector<long> voxel_of;
};

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

// Splits triangle t into k^2 congruent pieces (k from the spacing) and returns
// their centroids, each standing for area/k^2.
void SampleTriangle(const io::TriangleMesh& m, std::uint32_t t, double spacing,
                    std::vector<RawSample>* out) {
  const Eigen::Vector3d &a = m.corner(t, 0), &b = m.corner(t, 1), &c = m.corner(t, 2);
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

// Every triangle's samples with their voxels, in triangle order (blocks of triangles on the
// workers, concatenated in block order).
RawSamples SampleSurface(const io::TriangleMesh& m, const VoxelGrid& grid, double spacing,
                         int threads) {
  constexpr std::size_t kTrianglesPerBlock = 4096;
  const std::size_t blocks = (m.num_triangles() + kTrianglesPerBlock - 1) / kTrianglesPerBlock;
  std::vector<RawSamples> parts(blocks);
  detail::ParallelFor(blocks, threads, [&](std::size_t block, int) {
    RawSamples& part = parts[block];
    const std::size_t end = std::min(m.num_triangles(), (block + 1) * kTrianglesPerBlock);
    for (auto t = static_cast<std::uint32_t>(block * kTrianglesPerBlock); t < end; ++t) {
      const std::size_t first = part.samples.size();
      SampleTriangle(m, t, spacing, &part.samples);
      for (std::size_t i = first; i < part.samples.size(); ++i)
        part.voxel_of.push_back(FindSampleVoxel(grid, part.samples[i].p, t));
    }
  });
  RawSamples all;
  for (RawSamples& part : parts) {
    all.samples.insert(all.samples.end(), part.samples.begin(), part.samples.end());
    all.voxel_of.insert(all.voxel_of.end(), part.voxel_of.begin(), part.voxel_of.end());
    part = RawSamples();
  }
  return all;
}

// A sample's merge key: its voxel, its part and its sub-cell of the voxel.
struct MergeKey {
  long voxel;
  std::int32_t part;
  std::int64_t sub;
  std::uint32_t index;  ///< into the raw samples (ties keep the first)
  bool SameGroup(const MergeKey& o) const {
    return voxel == o.voxel && part == o.part && sub == o.sub;
  }
};

// The merge keys of the samples in a voxel (k^3 sub-cells per voxel), sorted.
std::vector<MergeKey> SortedMergeKeys(const VoxelGrid& grid, const io::TriangleMesh& mesh, int k,
                                      const RawSamples& raw) {
  const double s = grid.voxel_size_mm;
  std::vector<MergeKey> keyed;
  keyed.reserve(raw.samples.size());
  for (std::size_t i = 0; i < raw.samples.size(); ++i) {
    const long v = raw.voxel_of[i];
    if (v < 0) continue;
    const Eigen::Vector3d corner =
        grid.origin_F +
        s * MortonDecode(grid.surface_keys[static_cast<std::size_t>(v)]).cast<double>();
    std::int64_t sub = 0;
    for (int a = 3; a-- > 0;) {
      const double u = (raw.samples[i].p[a] - corner[a]) / s * k;
      sub = sub * k + std::clamp(static_cast<std::int64_t>(std::floor(u)), std::int64_t{0},
                                 std::int64_t{k - 1});
    }
    const std::uint32_t t = raw.samples[i].triangle;
    keyed.push_back({v, mesh.triangle_part.empty() ? 0 : mesh.triangle_part[t], sub,
                     static_cast<std::uint32_t>(i)});
  }
  std::sort(keyed.begin(), keyed.end(), [](const MergeKey& a, const MergeKey& b) {
    return std::tie(a.voxel, a.part, a.sub, a.index) < std::tie(b.voxel, b.part, b.sub, b.index);
  });
  return keyed;
}

// One merged sample from the group keyed[first, last): the member nearest the group's
// area-weighted centroid, carrying the group's area.
RawSample MergeGroup(const std::vector<MergeKey>& keyed, std::size_t first, std::size_t last,
                     const std::vector<RawSample>& raw) {
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  double area = 0.0;
  for (std::size_t j = first; j < last; ++j) {
    const RawSample& r = raw[keyed[j].index];
    weighted += r.area * r.p;
    area += r.area;
  }
  const Eigen::Vector3d centroid =
      area > 0.0 ? Eigen::Vector3d(weighted / area) : raw[keyed[first].index].p;
  std::uint32_t best = keyed[first].index;
  for (std::size_t j = first + 1; j < last; ++j) {
    const std::uint32_t i = keyed[j].index;
    if ((raw[i].p - centroid).squaredNorm() < (raw[best].p - centroid).squaredNorm()) best = i;
  }
  RawSample r = raw[best];
  r.area = area;
  return r;
}

// Merges the samples of small triangles so that the surface is sampled at
// about `spacing` wherever its triangles are finer than that: each upper voxel
// is split into k^3 sub-cells (k = ceil(voxel / spacing), so a sub-cell's edge
// is at most the spacing), and the samples of one part in one sub-cell become
// one: the member nearest their area-weighted centroid (a point of the
// surface, not a point between curved patches), carrying their total area.
// Samples outside every voxel (voxel_of < 0) are dropped as before. Output in
// (voxel, part, sub-cell) order; deterministic (ties keep the first member).
RawSamples MergeSamples(const VoxelGrid& grid, const io::TriangleMesh& mesh, double spacing,
                        const RawSamples& raw) {
  const int k = std::max(1, static_cast<int>(std::ceil(grid.voxel_size_mm / spacing - 1e-9)));
  const std::vector<MergeKey> keyed = SortedMergeKeys(grid, mesh, k, raw);
  RawSamples merged;
  for (std::size_t first = 0; first < keyed.size();) {
    std::size_t last = first + 1;
    while (last < keyed.size() && keyed[last].SameGroup(keyed[first])) ++last;
    merged.samples.push_back(MergeGroup(keyed, first, last, raw.samples));
    merged.voxel_of.push_back(keyed[first].voxel);
    first = last;
  }
  return merged;
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

void JawOracle::BuildUpperSide(std::shared_ptr<const io::TriangleMesh> upper_U, int threads) {
  upper_ = SphereTree::Build(
      std::move(upper_U), detail::OracleTreeOptions(options_, detail::OracleJaw::kUpper, threads));
  const io::TriangleMesh& up = upper_.mesh();
  PlaceSamples(up, threads);
  BuildVoxelSamples();
  BuildNodeLeafRanges();
  BuildCellSpheres();
  BuildNodeSampleSpheres();
  BuildSamplesSphere();
  // Anterior teeth by Universal number: 6..11 (upper), 22..27 (lower).
  for (const auto& part : up.parts) {
    const int t = part.tooth_number;
    part_has_tooth_.push_back(t > 0);
    part_is_anterior_tooth_.push_back((t >= 6 && t <= 11) || (t >= 22 && t <= 27));
  }
}

void JawOracle::PlaceSamples(const io::TriangleMesh& up, int threads) {
  const VoxelGrid& grid = upper_.grid();
  const double spacing = options_.sample_spacing_mm > 0 ? options_.sample_spacing_mm : 0.3;
  const RawSamples raw = MergeSamples(grid, up, spacing, SampleSurface(up, grid, spacing, threads));
  // Grouped by voxel (counting sort).
  const std::size_t nv = grid.num_surface();
  voxel_sample_begin_.assign(nv + 1, 0);
  for (const long v : raw.voxel_of) ++voxel_sample_begin_[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < nv; ++v) voxel_sample_begin_[v + 1] += voxel_sample_begin_[v];
  const std::size_t ns = voxel_sample_begin_[nv];
  OCCLUDE_ASSERT(ns == raw.samples.size(), "every merged sample lies in a voxel");
  sample_p_U_.resize(ns);
  sample_area_.resize(ns);
  sample_part_.resize(ns);
  std::vector<std::uint32_t> fill(voxel_sample_begin_.begin(), voxel_sample_begin_.end() - 1);
  // One representative sample per connected component of the upper surface,
  // with the component's sample count (CountNestedPieces).
  const std::vector<std::int32_t> component = detail::ComponentOfTriangle(up);
  std::vector<std::uint32_t> component_slot;
  for (std::size_t i = 0; i < raw.samples.size(); ++i) {
    const RawSample& r = raw.samples[i];
    const std::uint32_t slot = fill[static_cast<std::size_t>(raw.voxel_of[i])]++;
    sample_p_U_[slot] = r.p.cast<float>();
    sample_area_[slot] = static_cast<float>(r.area);
    sample_part_[slot] = up.triangle_part.empty() ? 0 : up.triangle_part[r.triangle];
    const auto c = static_cast<std::uint32_t>(component[r.triangle]);
    if (c >= component_slot.size()) component_slot.resize(c + 1, ~0u);
    if (component_slot[c] == ~0u) {
      component_slot[c] = static_cast<std::uint32_t>(component_samples_.size());
      component_samples_.push_back({slot, 0});
    }
    ++component_samples_[component_slot[c]].count;
  }
}

void JawOracle::BuildVoxelSamples() {
  // Voxel-level samples: area-weighted centroid and the dominant part.
  const VoxelGrid& grid = upper_.grid();
  const std::size_t nv = grid.num_surface();
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
    voxel_centroid_U_[v] = (area > 0 ? Eigen::Vector3d(c / area)
                                     : grid.VoxelCenter(MortonDecode(grid.surface_keys[v])))
                               .cast<float>();
    voxel_area_[v] = static_cast<float>(area);
    voxel_part_[v] = voxel_sample_begin_[v] < voxel_sample_begin_[v + 1]
                         ? sample_part_[voxel_sample_begin_[v]]
                         : 0;
  }
}

void JawOracle::BuildNodeLeafRanges() {
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
}

void JawOracle::BuildCellSpheres() {
  // Per cell (node of the query's cell level) and per voxel: the centre of
  // the samples' bounding box and their largest distance from it (the query's
  // culls). Samples and voxel centres are also stored as float offsets from
  // their cell's centre, the radii measured from those offsets.
  const Octree& oct = upper_.octree();
  const int level = std::min(options_.cell_level, oct.top_level);
  const std::uint32_t begin = oct.level_begin[static_cast<std::size_t>(level)];
  const std::uint32_t end = oct.level_end[static_cast<std::size_t>(level)];
  cell_center_U_.assign(end - begin, Eigen::Vector3f::Zero());
  cell_radius_.assign(end - begin, 0.0f);
  sample_offset_U_.assign(sample_p_U_.size(), Eigen::Vector4f::Zero());
  voxel_sphere_U_.assign(upper_.grid().num_surface(), Eigen::Vector4f::Zero());
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

void JawOracle::BuildNodeSampleSpheres() {
  // Per node at or above the cell level: its samples' bounding sphere, the
  // broad phase's spheres (CellRequest::b_spheres); radius -1 without samples.
  const Octree& oct = upper_.octree();
  if (oct.empty()) return;
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

void JawOracle::BuildSamplesSphere() {
  // The samples' bounding sphere (box centre, farthest sample), for CountNestedPieces.
  if (sample_p_U_.empty()) return;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
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

}  // namespace occlude::collision
