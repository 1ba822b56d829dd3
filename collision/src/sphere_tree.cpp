// SphereTree construction: voxelize, build the octree, precompute the explicit
// spheres, and gather the per-level statistics of the paper's figures.
#include "occlude/collision/sphere_tree.h"

#include <chrono>
#include <cmath>

#include "occlude/collision/sphere_table.h"

namespace occlude::collision {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double SphereVolume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }

}  // namespace

const char* ToString(SphereMode mode) {
  switch (mode) {
    case SphereMode::kSimple: return "simple";
    case SphereMode::kOptimized: return "optimized";
    case SphereMode::kExplicit: return "explicit";
  }
  return "?";
}

std::size_t ExplicitSpheres::MemoryBytes() const {
  return (cx.capacity() + cy.capacity() + cz.capacity() + radius.capacity()) * sizeof(double);
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
  tree.stats_.seconds_voxelize = SecondsSince(start);

  start = std::chrono::steady_clock::now();
  tree.octree_ = BuildOctree(tree.grid_);
  tree.stats_.seconds_octree = SecondsSince(start);

  const Octree& oct = tree.octree_;
  if (options.build_explicit && !oct.empty()) {
    start = std::chrono::steady_clock::now();
    const SphereMode from =
        options.explicit_from == SphereMode::kSimple ? SphereMode::kSimple : SphereMode::kOptimized;
    ExplicitSpheres& ex = tree.explicit_;
    ex.from = from;
    const std::size_t n = oct.num_nodes();
    ex.cx.resize(n);
    ex.cy.resize(n);
    ex.cz.resize(n);
    ex.radius.resize(n);
    for (int level = oct.top_level; level >= 0; --level) {
      for (std::uint32_t i = oct.level_begin[level]; i < oct.level_end[level]; ++i) {
        Eigen::Vector3d c;
        tree.ImplicitSphere(i, level, from, &c, &ex.radius[i]);
        ex.cx[i] = c.x();
        ex.cy[i] = c.y();
        ex.cz[i] = c.z();
      }
    }
    tree.stats_.seconds_explicit = SecondsSince(start);
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
  const io::TriangleMesh& m = *tree.mesh_;
  st.bytes_mesh = m.vertices.capacity() * sizeof(Eigen::Vector3d) +
                  m.triangles.capacity() * sizeof(Eigen::Vector3i) +
                  m.face_normals.capacity() * sizeof(Eigen::Vector3d) +
                  m.triangle_part.capacity() * sizeof(std::int32_t);
  return tree;
}

}  // namespace occlude::collision
