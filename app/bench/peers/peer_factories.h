// The peers' module's factories (module.cpp puts those it was built with into its Module).
#pragma once

#include <memory>
#include <string>

#include "bench/peer_module.h"

namespace occlude::app::peers {

/// Throws std::invalid_argument, `prefix` then what is wrong, for a mesh with no triangles, more
/// vertices or triangles than an int counts, or a triangle indexing past the vertices
/// (module.cpp).
void CheckPeerMesh(const io::TriangleMesh& mesh, const std::string& prefix);

/// Builds both jaws' BVH models (fcl_model.cpp); std::invalid_argument for an unusable mesh.
std::unique_ptr<FclModel> MakeFclModel(const io::TriangleMesh& lower_L,
                                       const io::TriangleMesh& upper_U, FclBv bv);

/// Builds the lower jaw's level set (openvdb_grid.cpp); std::invalid_argument for an unusable
/// mesh.
std::unique_ptr<OpenVdbGrid> MakeOpenVdbGrid(const io::TriangleMesh& lower_L, double voxel_mm,
                                             int half_width_voxels);

}  // namespace occlude::app::peers
