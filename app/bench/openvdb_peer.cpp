// The OpenVDB peer (see openvdb_peer.h): a front for the lower jaw's level set, which the peers'
// module builds and samples (bench/peer_module.h, bench/peers/openvdb_grid.cpp), so that
// OpenVDB is loaded only when a peer is made.
#include "bench/openvdb_peer.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "bench/peer_module.h"

namespace occlude::app {

struct OpenVdbPeer::Impl {
  double voxel_mm = 0.0;
  int half_width_voxels = 0;
  std::unique_ptr<peers::OpenVdbGrid> grid;
};

std::string OpenVdbPeer::Unavailable() {
#ifdef OCCLUDE_HAVE_OPENVDB
  return peers::WhyUnavailable(peers::Peer::kOpenVdb, true);
#else
  return peers::WhyUnavailable(peers::Peer::kOpenVdb, false);
#endif
}

bool OpenVdbPeer::Available() { return Unavailable().empty(); }

OpenVdbPeer::OpenVdbPeer(const io::TriangleMesh& lower_L, double voxel_mm, int half_width_voxels) {
  const std::string why_not = Unavailable();
  if (!why_not.empty()) throw std::runtime_error(why_not);
  if (!(voxel_mm > 0.0) || !std::isfinite(voxel_mm)) {
    throw std::invalid_argument("OpenVdbPeer: the voxel size must be finite and > 0 mm");
  }
  if (half_width_voxels < 1) {
    throw std::invalid_argument("OpenVdbPeer: the band's half width must be at least 1 voxel");
  }
  impl_ = std::make_unique<Impl>();
  impl_->voxel_mm = voxel_mm;
  impl_->half_width_voxels = half_width_voxels;
  impl_->grid = peers::LoadModule(nullptr)->make_openvdb(lower_L, voxel_mm, half_width_voxels);
}

OpenVdbPeer::~OpenVdbPeer() = default;
OpenVdbPeer::OpenVdbPeer(OpenVdbPeer&& other) noexcept = default;
OpenVdbPeer& OpenVdbPeer::operator=(OpenVdbPeer&& other) noexcept = default;

double OpenVdbPeer::voxel_mm() const { return impl_->voxel_mm; }
int OpenVdbPeer::half_width_voxels() const { return impl_->half_width_voxels; }
double OpenVdbPeer::build_seconds() const { return impl_->grid->build_seconds(); }
std::size_t OpenVdbPeer::approx_bytes() const { return impl_->grid->approx_bytes(); }
std::size_t OpenVdbPeer::active_voxels() const { return impl_->grid->active_voxels(); }

double OpenVdbPeer::Value(const Eigen::Vector3d& p_L) const { return impl_->grid->Value(p_L); }

OpenVdbSampleResult OpenVdbPeer::Sample(const std::vector<Eigen::Vector3f>& samples_U,
                                        const std::vector<float>& area_mm2,
                                        const Eigen::Isometry3d& X_LU,
                                        const OpenVdbCountRule& rule) const {
  return impl_->grid->Sample(samples_U, area_mm2, X_LU, rule);
}

}  // namespace occlude::app
