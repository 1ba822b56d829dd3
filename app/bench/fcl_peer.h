// The FCL peer: one jaw pair held as FCL 0.7 BVH models, so that `occlude bench` can time the
// general-purpose library on exactly the same meshes and poses as our Implicit Sphere Tree.
//
// FCL stays behind this header (pimpl) and in the peers' module (bench/peer_module.h), which is
// opened when the first peer is made: nothing here includes an FCL header, and `occlude` does
// not load FCL unless it benchmarks against it. Without FCL (OCCLUDE_HAVE_FCL undefined) or
// without the module, Available() returns false and the constructor throws std::runtime_error
// saying why (Unavailable()).
//
// Frames and units: the lower jaw's mesh is given in its own frame L and stays at identity;
// the upper jaw's mesh is given in its own frame U and every query places it by X_LU (the pose
// of U in L). All lengths are millimetres; every result is expressed in L.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// The bounding volume FCL builds its hierarchy from.
enum class FclBv {
  kOBB,     ///< oriented boxes: collision only (FCL 0.7 has no OBB mesh-mesh distance)
  kOBBRSS,  ///< oriented box + rectangle swept sphere: collision and distance
};

/// Short name for reports: "OBB" or "OBBRSS".
const char* FclBvName(FclBv bv);

/// What one FCL query answered (fields a query does not compute keep their defaults).
struct FclQueryResult {
  bool collide = false;      ///< boolean collide
  std::size_t contacts = 0;  ///< number of intersecting triangle pairs (all-contacts collide)
  double distance_mm = 0.0;  ///< minimum distance between the surfaces, mm; FCL reports 0 (not
                             ///< a penetration depth) when the meshes intersect
  Eigen::Vector3d p_L_on_lower = Eigen::Vector3d::Zero();  ///< nearest point on lower, in L, mm
  Eigen::Vector3d p_L_on_upper = Eigen::Vector3d::Zero();  ///< nearest point on upper, in L, mm
};

/// One jaw pair as FCL BVH models, built once in the constructor; queries only change the
/// upper jaw's pose. Queries are const and do not modify shared state, so one FclPeer may be
/// queried from several threads at once. A moved-from peer may only be destroyed or assigned to.
class FclPeer {
 public:
  /// True when occlude was built with FCL and its peers' module opens (bench/peer_module.h).
  static bool Available();
  /// Why no peer can be made (the missing package or module file and the fix); empty when one
  /// can.
  static std::string Unavailable();

  /// Builds both BVH models (meshes must be non-empty and consistent, else
  /// std::invalid_argument). lower_L: lower jaw in L; upper_U: upper jaw in U. Vertices and
  /// triangles are copied; the meshes need not outlive the peer.
  FclPeer(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_U, FclBv bv);
  ~FclPeer();
  FclPeer(FclPeer&& other) noexcept;
  FclPeer& operator=(FclPeer&& other) noexcept;
  FclPeer(const FclPeer&) = delete;
  FclPeer& operator=(const FclPeer&) = delete;

  FclBv bv() const;
  /// Wall-clock seconds the constructor spent building both models.
  double build_seconds() const;
  /// Approximate memory of both BVH models: nodes * sizeof(node) + vertices + triangles +
  /// primitive index arrays, bytes.
  std::size_t approx_bytes() const;

  /// Boolean collision at pose X_LU (FCL stops at the first intersecting triangle pair).
  bool Collide(const Eigen::Isometry3d& X_LU) const;
  /// Number of intersecting triangle pairs at pose X_LU, at most max_contacts (>= 1). FCL runs
  /// with enable_contact = false: then it adds exactly one contact per intersecting pair
  /// without computing contact points, whereas enable_contact = true computes up to two points
  /// per pair and counts each as a contact (so the count would no longer be the pair count).
  std::size_t CollideAll(const Eigen::Isometry3d& X_LU, std::size_t max_contacts = 100000) const;
  /// The intersecting triangle pairs at pose X_LU as (lower triangle, upper triangle) indices
  /// of the meshes given to the constructor, at most max_contacts (>= 1); the same query as
  /// CollideAll.
  std::vector<std::pair<std::size_t, std::size_t>> IntersectingPairs(
      const Eigen::Isometry3d& X_LU, std::size_t max_contacts = 100000) const;
  /// Minimum distance and the nearest points at pose X_LU (result.collide is set when the
  /// distance is 0). Only FclBv::kOBBRSS: FCL 0.7 registers no OBB mesh-mesh distance (it would
  /// print a warning and return no distance), so kOBB throws std::invalid_argument.
  FclQueryResult Distance(const Eigen::Isometry3d& X_LU) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace occlude::app
