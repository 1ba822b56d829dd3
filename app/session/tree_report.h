// Building the sphere trees of a jaw pair for a command, and describing them
// (what was built, how big, how long it took) in text and JSON.
#pragma once

#include <memory>
#include <string>

#include "occlude/collision/sphere_tree.h"

namespace occlude::app {

/// Builds a tree, turning VoxelizeError into a UserError that names `what`.
collision::SphereTree BuildTreeOrExplain(std::shared_ptr<const io::TriangleMesh> mesh,
                                         const collision::SphereTreeOptions& options,
                                         const std::string& what);

/// One line: voxels per class, nodes, build time per stage, memory.
std::string DescribeTree(const std::string& name, const collision::SphereTree& tree);

/// The same as a JSON object.
std::string TreeJson(const collision::SphereTree& tree);

}  // namespace occlude::app
