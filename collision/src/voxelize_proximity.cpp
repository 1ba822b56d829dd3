// Proximity stage of Voxelize. From the centre c of every surface voxel, for every
// triangle listed in it, the points c + h * s * n (n the triangle's unit outward
// normal, h = 1/2, 1, 3/2, ..., layers) fall in voxels (i,j,k) + floor(1/2 + h n);
// those voxels whose centres lie strictly on the outward side of the triangle's
// plane become Proximity voxels unless they are Surface voxels. The half steps
// close the gaps an oblique normal would leave between whole steps. The offsets
// depend only on the normal, so they are computed once per triangle.
#include <cmath>

#include "occlude/collision/morton.h"
#include "voxelize_detail.h"

namespace occlude::collision::detail {
namespace {

struct Offset {
  std::int16_t d[3] = {};
  bool operator==(const Offset& o) const {
    return d[0] == o.d[0] && d[1] == o.d[1] && d[2] == o.d[2];
  }
};

/// Unit outward normal of triangle t from its corners (the mesh convention: CCW seen
/// from outside); zero for a degenerate triangle.
Eigen::Vector3d OutwardNormal(const io::TriangleMesh& mesh, std::size_t t) {
  const Eigen::Vector3d n =
      (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

/// Per-triangle step offsets (distinct, non-zero), `stride` slots per triangle,
/// unused slots padded with zero offsets.
struct TriangleSteps {
  int stride = 0;
  std::vector<Offset> offsets;  // num_triangles * stride
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> plane;  // n . a per triangle
};

TriangleSteps ComputeSteps(const io::TriangleMesh& mesh, int layers) {
  TriangleSteps st;
  st.stride = 2 * layers;
  const std::size_t nt = mesh.num_triangles();
  st.offsets.assign(nt * static_cast<std::size_t>(st.stride), Offset{{0, 0, 0}});
  st.normals.resize(nt);
  st.plane.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const Eigen::Vector3d n = OutwardNormal(mesh, t);
    st.normals[t] = n;
    st.plane[t] = n.dot(mesh.corner(t, 0));
    Offset* out = &st.offsets[t * static_cast<std::size_t>(st.stride)];
    int used = 0;
    for (int q = 1; q <= st.stride; ++q) {
      Offset o;
      for (int a = 0; a < 3; ++a) {
        o.d[a] = static_cast<std::int16_t>(std::floor(0.5 + 0.5 * q * n[a]));
      }
      if (o == Offset{{0, 0, 0}} || std::find(out, out + used, o) != out + used) continue;
      out[used++] = o;
    }
  }
  return st;
}

/// A small direct-mapped set of recently emitted keys. Surface voxels are visited
/// in Morton order, so neighbours emit the same candidates again and again; this
/// drops most repeats before the global sort (which still removes the rest, so
/// the result does not depend on it).
class RecentKeys {
 public:
  /// True when `key` was recently inserted; otherwise remembers it.
  bool SeenOrInsert(std::uint64_t key) {
    std::uint64_t& slot = slots_[(key * 0x9E3779B97F4A7C15ULL) >> (64 - kBits)];
    if (slot == key + 1) return true;
    slot = key + 1;  // 0 means empty
    return false;
  }

 private:
  static constexpr int kBits = 12;
  std::vector<std::uint64_t> slots_ = std::vector<std::uint64_t>(std::size_t{1} << kBits, 0);
};

/// Appends the proximity candidates of surface voxel v to `candidates`;
/// `local` is scratch for this voxel's distinct offsets.
void VoxelCandidates(const VoxelGrid& grid, const GridFrame& f, const TriangleSteps& st,
                     std::size_t v, std::vector<Offset>* local, RecentKeys* recent,
                     std::vector<std::uint64_t>* candidates) {
  const Eigen::Vector3i ijk = MortonDecode(grid.surface_keys[v]);
  const Eigen::Vector3d c(f.Center(0, ijk.x()), f.Center(1, ijk.y()), f.Center(2, ijk.z()));
  local->clear();
  for (std::uint32_t n = grid.triangles_begin(v); n < grid.triangles_end(v); ++n) {
    const std::uint32_t t = grid.triangle_indices[n];
    const Eigen::Vector3d& normal = st.normals[t];
    const double height = normal.dot(c) - st.plane[t];  // signed distance of c to the plane
    const Offset* steps = &st.offsets[t * static_cast<std::size_t>(st.stride)];
    for (int q = 0; q < st.stride; ++q) {
      const Offset& o = steps[q];
      if (o == Offset{{0, 0, 0}}) break;
      const double dh = normal.x() * o.d[0] + normal.y() * o.d[1] + normal.z() * o.d[2];
      if (height + f.s * dh <= 0.0) continue;  // not on the outward side
      if (std::find(local->begin(), local->end(), o) == local->end()) local->push_back(o);
    }
  }
  for (const Offset& o : *local) {
    const Eigen::Vector3i q = ijk + Eigen::Vector3i(o.d[0], o.d[1], o.d[2]);
    if ((q.array() < 0).any() || (q.array() >= f.dims.array()).any()) continue;
    const std::uint64_t key = MortonEncode(q);
    if (!recent->SeenOrInsert(key)) candidates->push_back(key);
  }
}

}  // namespace

void BuildProximity(const io::TriangleMesh& mesh, const GridFrame& frame, int layers,
                    VoxelGrid* grid) {
  if (layers <= 0 || grid->surface_keys.empty()) return;
  const TriangleSteps steps = ComputeSteps(mesh, layers);
  std::vector<std::uint64_t> candidates;
  candidates.reserve(grid->surface_keys.size() * static_cast<std::size_t>(layers));
  std::vector<Offset> local;
  RecentKeys recent;
  for (std::size_t v = 0; v < grid->surface_keys.size(); ++v) {
    VoxelCandidates(*grid, frame, steps, v, &local, &recent, &candidates);
  }
  SortUnique(candidates, frame.key_bits());
  grid->proximity_keys = SortedDifference(candidates, grid->surface_keys);
}

}  // namespace occlude::collision::detail
