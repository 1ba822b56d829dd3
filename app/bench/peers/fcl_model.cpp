// The FCL half of the peers' module (see bench/peer_module.h and fcl_peer.h): builds FCL 0.7
// BVH models of a jaw pair once and answers collide / all-contacts / distance queries for a pose
// X_LU of the upper jaw in the lower jaw's frame L.
#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "bench/peer_module.h"
#include "bench/peers/peer_factories.h"

// FCL's headers reach us as system headers (/usr/include, imported target), so our warning
// set (-Werror) does not apply to them; no diagnostic pragmas are needed with FCL 0.7.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

namespace occlude::app::peers {
namespace {

// A BVH model of `mesh` (coordinates kept in the mesh's own frame, mm) with FCL's default
// splitter and fitter for BV. The triangle order is the mesh's, so FCL's primitive ids are
// our triangle indices.
template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> BuildModel(const io::TriangleMesh& mesh, std::size_t* bytes) {
  std::vector<fcl::Vector3d> points(mesh.vertices.begin(), mesh.vertices.end());
  std::vector<fcl::Triangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    triangles.emplace_back(static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                           static_cast<std::size_t>(t[2]));
  }
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  const int nt = static_cast<int>(triangles.size());
  const int nv = static_cast<int>(points.size());
  if (model->beginModel(nt, nv) != fcl::BVH_OK || model->addSubModel(points, triangles) != 0 ||
      model->endModel() != fcl::BVH_OK) {
    throw std::runtime_error("FclPeer: FCL failed to build a BVH model");
  }
  // Nodes, vertices, triangles and the primitive index array FCL keeps per triangle.
  *bytes += static_cast<std::size_t>(model->getNumBVs()) * sizeof(fcl::BVNode<BV>) +
            points.size() * sizeof(fcl::Vector3d) +
            triangles.size() * (sizeof(fcl::Triangle) + sizeof(unsigned int));
  return model;
}

// Both jaws as CollisionObjects at identity, built once. Queries never call setTransform:
// they pass the objects' geometry with the lower transform (identity) and X_LU to FCL's
// geometry+transform overloads of collide/distance, which is exactly what the
// CollisionObject overloads do internally. So queries are const and share no mutable state
// (safe from several threads). Measured on a-bite-3shape (68k upper vertices): this and a
// mutable upper object with setTransform both add about 0.2 us per query; building a
// CollisionObject per query adds 0.26-0.36 ms (its constructor rescans every vertex in
// computeLocalAABB, and writes to the shared geometry), and a mutable member would need a lock.
static_assert(std::is_same_v<fcl::Transform3d, Eigen::Isometry3d>,
              "FCL's Transform3d is expected to be Eigen::Isometry3d");

class FclModelImpl final : public FclModel {
 public:
  FclModelImpl(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_U, FclBv bv) {
    CheckPeerMesh(lower_L, "FclPeer: lower jaw mesh ");
    CheckPeerMesh(upper_U, "FclPeer: upper jaw mesh ");
    const auto t0 = std::chrono::steady_clock::now();
    std::shared_ptr<fcl::CollisionGeometryd> lower_geometry;
    std::shared_ptr<fcl::CollisionGeometryd> upper_geometry;
    if (bv == FclBv::kOBB) {
      lower_geometry = BuildModel<fcl::OBBd>(lower_L, &bytes_);
      upper_geometry = BuildModel<fcl::OBBd>(upper_U, &bytes_);
    } else {
      lower_geometry = BuildModel<fcl::OBBRSSd>(lower_L, &bytes_);
      upper_geometry = BuildModel<fcl::OBBRSSd>(upper_U, &bytes_);
    }
    // The constructor computes each geometry's local AABB once (a pass over its vertices).
    lower_ = std::make_unique<fcl::CollisionObjectd>(lower_geometry);
    upper_ = std::make_unique<fcl::CollisionObjectd>(upper_geometry);
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  double build_seconds() const override { return build_seconds_; }
  std::size_t approx_bytes() const override { return bytes_; }

  std::size_t CountPairs(const Eigen::Isometry3d& X_LU, std::size_t max_contacts) const override {
    return Collide(X_LU, max_contacts).numContacts();
  }

  std::vector<std::pair<std::size_t, std::size_t>> IntersectingPairs(
      const Eigen::Isometry3d& X_LU, std::size_t max_contacts) const override {
    const fcl::CollisionResultd result = Collide(X_LU, max_contacts);
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (std::size_t i = 0; i < result.numContacts(); ++i) {
      const fcl::Contactd& c = result.getContact(i);
      pairs.emplace_back(static_cast<std::size_t>(c.b1), static_cast<std::size_t>(c.b2));
    }
    return pairs;
  }

  FclQueryResult Distance(const Eigen::Isometry3d& X_LU) const override {
    // enable_signed_distance stays false: for meshes FCL would only re-run collide to guess a
    // depth; intersecting meshes simply report 0.
    fcl::DistanceRequestd request(/*enable_nearest_points=*/true);
    fcl::DistanceResultd result;
    fcl::distance(lower_->collisionGeometry().get(), lower_->getTransform(),
                  upper_->collisionGeometry().get(), X_LU, request, result);
    FclQueryResult out;
    out.distance_mm = result.min_distance;
    out.collide = result.min_distance <= 0.0;
    // FCL returns the nearest points in its world frame, which is L (the lower jaw is at
    // identity).
    out.p_L_on_lower = result.nearest_points[0];
    out.p_L_on_upper = result.nearest_points[1];
    return out;
  }

 private:
  // FCL with enable_contact = false adds exactly one contact per intersecting pair.
  fcl::CollisionResultd Collide(const Eigen::Isometry3d& X_LU, std::size_t max_contacts) const {
    fcl::CollisionRequestd request(max_contacts, /*enable_contact=*/false);
    fcl::CollisionResultd result;
    fcl::collide(lower_->collisionGeometry().get(), lower_->getTransform(),
                 upper_->collisionGeometry().get(), X_LU, request, result);
    return result;
  }

  double build_seconds_ = 0.0;
  std::size_t bytes_ = 0;
  std::unique_ptr<fcl::CollisionObjectd> lower_;  // lower jaw, frame L, identity
  std::unique_ptr<fcl::CollisionObjectd> upper_;  // upper jaw, frame U, placed per query
};

}  // namespace

std::unique_ptr<FclModel> MakeFclModel(const io::TriangleMesh& lower_L,
                                       const io::TriangleMesh& upper_U, FclBv bv) {
  return std::make_unique<FclModelImpl>(lower_L, upper_U, bv);
}

}  // namespace occlude::app::peers
