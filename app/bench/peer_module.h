// The benchmark peers' module: FCL and OpenVDB are linked into a shared object of their own,
// libocclude_peers.so beside the binary, which FclPeer and OpenVdbPeer open (dlopen) the first
// time a peer is asked for. Linked into `occlude` itself, the two libraries and theirs (octomap,
// Boost, Blosc, log4cplus, Imath) cost every run of every command about 0.05 s and 30 MB before
// main (docs/results/speed/README.md), and only `occlude bench` uses them.
//
// The module is built from app/bench/peers/ with the same compiler and flags as the binary, so
// C++ types (meshes, results, exceptions) cross the boundary as they are; kModuleVersion guards
// against a module left over from another build.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bench/fcl_peer.h"
#include "bench/openvdb_peer.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::app::peers {

/// Raised whenever what crosses the boundary changes.
inline constexpr int kModuleVersion = 1;

/// A jaw pair as FCL BVH models (FclPeer's queries; see fcl_peer.h).
class FclModel {
 public:
  virtual ~FclModel() = default;
  virtual double build_seconds() const = 0;
  virtual std::size_t approx_bytes() const = 0;
  virtual std::size_t CountPairs(const Eigen::Isometry3d& X_LU, std::size_t max_contacts) const = 0;
  virtual std::vector<std::pair<std::size_t, std::size_t>> IntersectingPairs(
      const Eigen::Isometry3d& X_LU, std::size_t max_contacts) const = 0;
  virtual FclQueryResult Distance(const Eigen::Isometry3d& X_LU) const = 0;
};

/// A lower jaw as an OpenVDB narrow-band level set (OpenVdbPeer's queries; see openvdb_peer.h).
class OpenVdbGrid {
 public:
  virtual ~OpenVdbGrid() = default;
  virtual double build_seconds() const = 0;
  virtual std::size_t approx_bytes() const = 0;
  virtual std::size_t active_voxels() const = 0;
  virtual double Value(const Eigen::Vector3d& p_L) const = 0;
  virtual OpenVdbSampleResult Sample(const std::vector<Eigen::Vector3f>& samples_U,
                                     const std::vector<float>& area_mm2,
                                     const Eigen::Isometry3d& X_LU,
                                     const OpenVdbCountRule& rule) const = 0;
};

/// What the module offers: a factory per peer it was built with (null without that library).
struct Module {
  int version = kModuleVersion;
  std::unique_ptr<FclModel> (*make_fcl)(const io::TriangleMesh& lower_L,
                                        const io::TriangleMesh& upper_U, FclBv bv) = nullptr;
  std::unique_ptr<OpenVdbGrid> (*make_openvdb)(const io::TriangleMesh& lower_L, double voxel_mm,
                                               int half_width_voxels) = nullptr;
};

/// The module's file name, looked for in the folder of the running binary.
inline constexpr const char* kModuleFile = "libocclude_peers.so";

/// The module, opened once (thread-safe); nullptr when it cannot be, with the reason in
/// *why_not (the file and the fix).
const Module* LoadModule(std::string* why_not);

/// The peers the module may hold.
enum class Peer { kFcl, kOpenVdb };

/// Why no `peer` can be made: the build had not its library (`built_with` false: the packages
/// to install), the module does not open, or it was built without it; empty when one can.
std::string WhyUnavailable(Peer peer, bool built_with);

}  // namespace occlude::app::peers

/// The module's one exported symbol.
extern "C" const occlude::app::peers::Module* occlude_peers_module();
