// The FCL peer (see fcl_peer.h): a front for the jaw pair's FCL models, which the peers' module
// builds and queries (bench/peer_module.h, bench/peers/fcl_model.cpp), so that FCL is loaded
// only when a peer is made.
#include "bench/fcl_peer.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "bench/peer_module.h"

namespace occlude::app {

struct FclPeer::Impl {
  FclBv bv = FclBv::kOBBRSS;
  std::unique_ptr<peers::FclModel> model;
};

std::string FclPeer::Unavailable() {
#ifdef OCCLUDE_HAVE_FCL
  return peers::WhyUnavailable(peers::Peer::kFcl, true);
#else
  return peers::WhyUnavailable(peers::Peer::kFcl, false);
#endif
}

bool FclPeer::Available() { return Unavailable().empty(); }

const char* FclBvName(FclBv bv) { return bv == FclBv::kOBB ? "OBB" : "OBBRSS"; }

FclPeer::FclPeer(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_U, FclBv bv) {
  const std::string why_not = Unavailable();
  if (!why_not.empty()) throw std::runtime_error(why_not);
  impl_ = std::make_unique<Impl>();
  impl_->bv = bv;
  impl_->model = peers::LoadModule(nullptr)->make_fcl(lower_L, upper_U, bv);
}

FclPeer::~FclPeer() = default;
FclPeer::FclPeer(FclPeer&& other) noexcept = default;
FclPeer& FclPeer::operator=(FclPeer&& other) noexcept = default;

FclBv FclPeer::bv() const { return impl_->bv; }
double FclPeer::build_seconds() const { return impl_->model->build_seconds(); }
std::size_t FclPeer::approx_bytes() const { return impl_->model->approx_bytes(); }

bool FclPeer::Collide(const Eigen::Isometry3d& X_LU) const {
  return impl_->model->CountPairs(X_LU, 1) > 0;
}

std::size_t FclPeer::CollideAll(const Eigen::Isometry3d& X_LU, std::size_t max_contacts) const {
  return impl_->model->CountPairs(X_LU, std::max<std::size_t>(max_contacts, 1));
}

std::vector<std::pair<std::size_t, std::size_t>> FclPeer::IntersectingPairs(
    const Eigen::Isometry3d& X_LU, std::size_t max_contacts) const {
  return impl_->model->IntersectingPairs(X_LU, std::max<std::size_t>(max_contacts, 1));
}

FclQueryResult FclPeer::Distance(const Eigen::Isometry3d& X_LU) const {
  if (impl_->bv != FclBv::kOBBRSS) {
    throw std::invalid_argument(
        "FclPeer::Distance: FCL 0.7 has no mesh-mesh distance for OBB models (build the peer "
        "with FclBv::kOBBRSS)");
  }
  return impl_->model->Distance(X_LU);
}

}  // namespace occlude::app
