// Tree building and description for the commands (see tree_report.h).
#include "session/tree_report.h"

#include <cstdio>
#include <sstream>

#include "base/user_error.h"

namespace occlude::app {

collision::SphereTree BuildTreeOrExplain(std::shared_ptr<const io::TriangleMesh> mesh,
                                         const collision::SphereTreeOptions& options,
                                         const std::string& what) {
  try {
    return collision::SphereTree::Build(std::move(mesh), options);
  } catch (const collision::VoxelizeError& e) {
    throw UserError(what + ": " + e.what());
  }
}

std::string DescribeTree(const std::string& name, const collision::SphereTree& tree) {
  const auto& st = tree.stats();
  char line[512];
  std::snprintf(line, sizeof line,
                "%-6s %8zu triangles, voxel %.3g mm: %zu surface, %zu proximity, %zu interior "
                "voxels; %zu nodes in %d levels; build %.0f ms (voxelize %.0f, octree %.0f, "
                "explicit %.0f); %.1f MB",
                name.c_str(), tree.mesh().num_triangles(), tree.voxel_size_mm(),
                st.voxelize.surface_voxels, st.voxelize.proximity_voxels,
                st.voxelize.interior_voxels, st.nodes, tree.octree().top_level + 1,
                1e3 * st.total_seconds(), 1e3 * st.seconds_voxelize, 1e3 * st.seconds_octree,
                1e3 * st.seconds_explicit, static_cast<double>(st.total_bytes()) / 1e6);
  return line;
}

std::string TreeJson(const collision::SphereTree& tree) {
  const auto& st = tree.stats();
  std::ostringstream s;
  s << "{\"triangles\": " << tree.mesh().num_triangles()
    << ", \"voxel_mm\": " << tree.voxel_size_mm()
    << ", \"surface_voxels\": " << st.voxelize.surface_voxels
    << ", \"proximity_voxels\": " << st.voxelize.proximity_voxels
    << ", \"interior_voxels\": " << st.voxelize.interior_voxels << ", \"nodes\": " << st.nodes
    << ", \"levels\": " << tree.octree().top_level + 1
    << ", \"seconds_voxelize\": " << st.seconds_voxelize
    << ", \"seconds_octree\": " << st.seconds_octree
    << ", \"seconds_explicit\": " << st.seconds_explicit << ", \"bytes\": " << st.total_bytes()
    << "}";
  return s.str();
}

}  // namespace occlude::app
