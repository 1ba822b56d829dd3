// The sphere-tree options of a JawOracle's two jaws, for its build (oracle_build.cpp,
// oracle_samples.cpp) and its memory estimate (memory_estimate.cpp) alike.
#pragma once

#include "occlude/collision/oracle.h"
#include "occlude/collision/sphere_tree.h"

namespace occlude::collision::detail {

enum class OracleJaw { kLower, kUpper };

/// The oracle's voxel size; the structures only tree-pair queries read (both trees' explicit
/// spheres, the upper's distance bound) when options.tree_queries; the lower's distance bound
/// always (the oracle's queries read it).
inline SphereTreeOptions OracleTreeOptions(const OracleOptions& options, OracleJaw jaw,
                                           int threads) {
  SphereTreeOptions tree;
  tree.voxelize.voxel_size_mm = options.voxel_size_mm;
  tree.build_explicit = options.tree_queries;
  tree.build_distance_bound = jaw == OracleJaw::kLower || options.tree_queries;
  tree.threads = threads;
  return tree;
}

}  // namespace occlude::collision::detail
