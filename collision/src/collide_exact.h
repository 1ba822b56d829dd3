// Private: exact triangle-level refinement of the voxel pairs of a query.
#pragma once

#include "occlude/collision/collide.h"

namespace occlude::collision {

/// Turns result->pairs into unique triangle pairs, keeps those within delta_mm
/// (exact triangle-triangle distance) as result->contacts, and sets
/// triangles_intersect, min_distance_mm and closest.
void RefineExact(const SphereTree& a, const SphereTree& b, const Eigen::Isometry3d& X_AB,
                 double delta_mm, CollisionResult* result);

}  // namespace occlude::collision
