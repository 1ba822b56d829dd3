// SphereTree construction: voxelize, build the octree, precompute the explicit
// spheres, and gather the per-level statistics of the paper's figures.
#include "occlude/collision/sphere_tree.h"

#include <chrono>
#include <cmath>
#include <limits>

#include "occlude/angles.h"
#include "occlude/collision/sphere_table.h"
#include "seconds_since.h"

namespace occlude::collision {
namespace {

double SphereVolume(double r) { return 4.0 / 3.0 * kPi * r * r * r; }

// A node's normal counts as coherent when the summed area-weighted normals keep
// at least this fraction of the summed areas (otherwise the surface folds back
// within the node and a slab would be as thick as the sphere).
constexpr double kCoherentNormal = 0.2;

// Computes the slabs of `ex` (spheres already set): normals bottom-up from the
// triangles of each voxel, then each voxel cube's projection range onto every
// ancestor's normal.
void BuildSlabs(const io::TriangleMesh& mesh, const VoxelGrid& grid, const Octree& oct,
                ExplicitSpheres* ex) {
  const std::size_t n = oct.num_nodes();
  std::vector<Eigen::Vector3d> sum(n, Eigen::Vector3d::Zero());
  std::vector<double> area(n, 0.0);
  std::vector<std::uint32_t> parent(n, 0);
  for (std::uint32_t node = 0; node < oct.leaf_begin(); ++node) {
    std::uint32_t child = oct.first_child[node];
    for (unsigned m = oct.child_mask[node]; m != 0; m &= m - 1) parent[child++] = node;
  }
  for (std::size_t v = 0; v < grid.num_surface(); ++v) {
    const std::size_t leaf = oct.leaf_begin() + v;
    for (auto i = grid.triangles_begin(v); i < grid.triangles_end(v); ++i) {
      const std::uint32_t t = grid.triangle_indices[i];
      const Eigen::Vector3d cross =
          (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
      sum[leaf] += cross;  // 2 * area * normal
      area[leaf] += cross.norm();
    }
  }
  for (std::size_t node = n; node-- > 1;) {  // children have larger indices than parents
    sum[parent[node]] += sum[node];
    area[parent[node]] += area[node];
  }
  std::vector<Eigen::Vector3d> normal(n);
  std::vector<double> lo(n, std::numeric_limits<double>::infinity());
  std::vector<double> hi(n, -std::numeric_limits<double>::infinity());
  std::vector<bool> coherent(n);
  for (std::size_t node = 0; node < n; ++node) {
    const double len = sum[node].norm();
    coherent[node] = area[node] > 0.0 && len >= kCoherentNormal * area[node];
    const Eigen::Vector3d unit =
        coherent[node] ? Eigen::Vector3d(sum[node] / len) : Eigen::Vector3d::UnitZ();
    // Store as float and use the float value everywhere, so build and query agree.
    ExplicitNode& rec = ex->nodes[node];
    rec.nx = static_cast<float>(unit.x());
    rec.ny = static_cast<float>(unit.y());
    rec.nz = static_cast<float>(unit.z());
    normal[node] = Eigen::Vector3d(static_cast<double>(rec.nx), static_cast<double>(rec.ny),
                                   static_cast<double>(rec.nz));
  }
  const double h = 0.5 * grid.voxel_size_mm;
  for (std::size_t v = 0; v < grid.num_surface(); ++v) {
    const std::uint32_t leaf = oct.leaf_begin() + static_cast<std::uint32_t>(v);
    const Eigen::Vector3d c = grid.origin_F + grid.voxel_size_mm * (oct.coord[leaf].cast<double>() +
                                                                    Eigen::Vector3d::Constant(0.5));
    for (std::uint32_t node = leaf;; node = parent[node]) {
      const ExplicitNode& rec = ex->nodes[node];
      const Eigen::Vector3d centre(rec.cx, rec.cy, rec.cz);
      const double proj = (c - centre).dot(normal[node]);
      const double half = h * normal[node].cwiseAbs().sum();
      lo[node] = std::min(lo[node], proj - half);
      hi[node] = std::max(hi[node], proj + half);
      if (node == 0) break;
    }
  }
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (std::size_t node = 0; node < n; ++node) {
    const double r = ex->nodes[node].radius;
    const double l = coherent[node] ? std::max(lo[node], -r) : -r;
    const double u = coherent[node] ? std::min(hi[node], r) : r;
    ex->nodes[node].slab_lo = std::nextafter(static_cast<float>(l), -kInf);
    ex->nodes[node].slab_hi = std::nextafter(static_cast<float>(u), kInf);
  }
}

}  // namespace

const char* ToString(SphereMode mode) {
  switch (mode) {
    case SphereMode::kSimple:
      return "simple";
    case SphereMode::kOptimized:
      return "optimized";
    case SphereMode::kExplicit:
      return "explicit";
  }
  return "?";
}

Eigen::Vector3d SphereTree::CubeCenter(std::size_t node, int level) const {
  return grid_.origin_F +
         edge(level) * (octree_.coord[node].cast<double>() + Eigen::Vector3d::Constant(0.5));
}

void SphereTree::ImplicitSphere(std::size_t node, int level, SphereMode mode,
                                Eigen::Vector3d* center, double* radius) const {
  const double e = edge(level);
  if (mode == SphereMode::kOptimized) {
    const UnitSphere& u = OptimizedSphereTable()[octree_.child_mask[node]];
    *center = CubeCenter(node, level) + e * u.center;
    *radius = e * u.radius;
  } else {
    *center = CubeCenter(node, level);
    *radius = SimpleRadius(e);
  }
}

SphereTree SphereTree::Build(std::shared_ptr<const io::TriangleMesh> mesh_F,
                             const SphereTreeOptions& options) {
  SphereTree tree;
  tree.mesh_ = std::move(mesh_F);
  auto start = std::chrono::steady_clock::now();
  tree.grid_ = Voxelize(*tree.mesh_, options.voxelize, &tree.stats_.voxelize);
  tree.stats_.seconds_voxelize = detail::SecondsSince(start);

  start = std::chrono::steady_clock::now();
  tree.octree_ = BuildOctree(tree.grid_);
  tree.stats_.seconds_octree = detail::SecondsSince(start);

  const Octree& oct = tree.octree_;
  if (options.build_explicit && !oct.empty()) {
    start = std::chrono::steady_clock::now();
    const SphereMode from =
        options.explicit_from == SphereMode::kSimple ? SphereMode::kSimple : SphereMode::kOptimized;
    ExplicitSpheres& ex = tree.explicit_;
    ex.from = from;
    const std::size_t n = oct.num_nodes();
    ex.nodes.resize(n);
    for (int level = oct.top_level; level >= 0; --level) {
      for (std::uint32_t i = oct.level_begin[level]; i < oct.level_end[level]; ++i) {
        Eigen::Vector3d c;
        tree.ImplicitSphere(i, level, from, &c, &ex.nodes[i].radius);
        ex.nodes[i].cx = c.x();
        ex.nodes[i].cy = c.y();
        ex.nodes[i].cz = c.z();
      }
    }
    BuildSlabs(*tree.mesh_, tree.grid_, oct, &ex);
    ex.compact.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const ExplicitNode& e = ex.nodes[i];
      const Eigen::Vector3f c(static_cast<float>(e.cx), static_cast<float>(e.cy),
                              static_cast<float>(e.cz));
      // Each coordinate rounds by at most 2^-24 of its size (2^-23 to be safe).
      const double grow =
          std::sqrt(3.0) *
          std::ldexp(std::max({std::abs(e.cx), std::abs(e.cy), std::abs(e.cz)}), -23);
      float r = static_cast<float>(e.radius + grow);
      while (static_cast<double>(r) < e.radius + grow)
        r = std::nextafter(r, std::numeric_limits<float>::infinity());
      ex.compact[i] = Eigen::Vector4f(c.x(), c.y(), c.z(), r);
    }
    tree.stats_.seconds_explicit = detail::SecondsSince(start);
  }

  if (options.build_distance_bound && !oct.empty()) {
    start = std::chrono::steady_clock::now();
    tree.bound_ = DistanceBound::Build(tree.grid_, DistanceBound::kMaxVoxels,
                                       DistanceBound::DefaultLevels(), options.threads);
    tree.stats_.seconds_bound = detail::SecondsSince(start);
  }

  SphereTreeStats& st = tree.stats_;
  st.nodes = oct.num_nodes();
  st.leaves = oct.num_leaves();
  const auto& table = OptimizedSphereTable();
  for (int level = 0; level <= oct.top_level; ++level) {
    LevelStats ls;
    ls.level = level;
    ls.nodes = oct.level_size(level);
    const double e = tree.edge(level);
    ls.simple_volume_mm3 = static_cast<double>(ls.nodes) * SphereVolume(SimpleRadius(e));
    for (std::uint32_t i = oct.level_begin[level]; i < oct.level_end[level]; ++i) {
      ls.optimized_volume_mm3 += SphereVolume(e * table[oct.child_mask[i]].radius);
    }
    st.levels.push_back(ls);
  }
  st.bytes_grid = tree.grid_.MemoryBytes();
  st.bytes_octree = oct.MemoryBytes();
  st.bytes_explicit = tree.explicit_.MemoryBytes();
  st.bytes_bound = tree.bound_.MemoryBytes();
  const io::TriangleMesh& m = *tree.mesh_;
  st.bytes_mesh = m.vertices.capacity() * sizeof(Eigen::Vector3d) +
                  m.triangles.capacity() * sizeof(Eigen::Vector3i) +
                  m.face_normals.capacity() * sizeof(Eigen::Vector3d) +
                  m.triangle_part.capacity() * sizeof(std::int32_t);
  return tree;
}

}  // namespace occlude::collision
