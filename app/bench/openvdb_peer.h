// The OpenVDB peer: what an engineer would use for "the signed distance of many points to a
// mesh" without our oracle, a sparse narrow-band level set (OpenVDB's meshToLevelSet) of the
// lower jaw, sampled trilinearly through a value accessor at the oracle's own upper samples, so
// that `occlude bench` can time it on exactly the same points and poses as the sub-voxel oracle.
//
// OpenVDB stays behind this header (pimpl) and in the peers' module (bench/peer_module.h), which
// is opened when the first peer is made: nothing here includes an OpenVDB header, and `occlude`
// does not load OpenVDB unless it benchmarks against it. Without OpenVDB (OCCLUDE_HAVE_OPENVDB
// undefined) or without the module, Available() returns false and the constructor throws
// std::runtime_error saying why (Unavailable()).
//
// Frames and units: the lower jaw's mesh is given in its own frame L, which is the level set's
// world frame (OpenVDB's linear transform of the voxel size, no offset: voxel (i, j, k) is
// centred at voxel * (i, j, k) in L); upper samples are given in the upper's frame U and every
// query places them by X_LU (the pose of U in L). Lengths are millimetres, areas mm^2. The
// sign is OpenVDB's level-set sign: negative inside the lower jaw, as the oracle's.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// How a sampled signed distance d counts: as JawOracle::Accumulate counts it.
struct OpenVdbCountRule {
  double contact_band_mm = 0.1;  ///< contact: 0 <= d <= band
  /// Penetration: d < 0 and -d <= this (the oracle's penetration search plus its field's band).
  double penetration_depth_mm = 0.7;
};

/// What one sampling of the upper samples answered (the oracle's totals, same definitions).
struct OpenVdbSampleResult {
  std::size_t contact_samples = 0;
  double contact_area_mm2 = 0.0;
  std::size_t penetration_samples = 0;
  double penetration_area_mm2 = 0.0;
  double max_penetration_mm = 0.0;  ///< deepest measured depth (>= 0)
  /// Samples deeper inside than the band (OpenVDB's interior background value): the oracle's
  /// deep_samples.
  std::size_t deep_samples = 0;
  /// Smallest signed distance among the samples within the band (+inf if none). Every sample
  /// is looked up, so this is exact within the band, unlike the culled oracle's.
  double min_distance_mm = std::numeric_limits<double>::infinity();
  std::size_t samples_evaluated = 0;
};

/// One lower jaw as an OpenVDB narrow-band level set (FloatGrid), built once in the
/// constructor. Queries are const and share no mutable state (each makes its own value
/// accessor), so one peer may be queried from several threads at once.
class OpenVdbPeer {
 public:
  /// True when occlude was built with OpenVDB and its peers' module opens (bench/peer_module.h).
  static bool Available();
  /// Why no peer can be made (the missing package or module file and the fix); empty when one
  /// can.
  static std::string Unavailable();

  /// Builds the level set of lower_L at voxel_mm (> 0) with a narrow band of half_width_voxels
  /// (>= 1) on either side of the surface: |d| < half_width_voxels * voxel_mm is known, deeper
  /// or farther points read the background value, +-that. The mesh must be non-empty with
  /// valid indices (else std::invalid_argument). OpenVDB takes its sign from the surface's
  /// closure (a flood fill from outside), not from the triangles' orientation: the mesh should
  /// be closed. OpenVDB's build runs on every core (oneTBB); build_seconds() is wall time.
  OpenVdbPeer(const io::TriangleMesh& lower_L, double voxel_mm, int half_width_voxels);
  ~OpenVdbPeer();
  OpenVdbPeer(OpenVdbPeer&& other) noexcept;
  OpenVdbPeer& operator=(OpenVdbPeer&& other) noexcept;
  OpenVdbPeer(const OpenVdbPeer&) = delete;
  OpenVdbPeer& operator=(const OpenVdbPeer&) = delete;

  double voxel_mm() const;
  int half_width_voxels() const;
  /// Wall-clock seconds the constructor spent (mesh copy into OpenVDB's arrays and the build).
  double build_seconds() const;
  /// The grid's memory (OpenVDB's Grid::memUsage), bytes.
  std::size_t approx_bytes() const;
  /// Active voxels of the narrow band.
  std::size_t active_voxels() const;

  /// The trilinear signed distance at p_L, mm (the background +-half width outside the band).
  double Value(const Eigen::Vector3d& p_L) const;
  /// Samples every point of samples_U placed by X_LU (trilinear, OpenVDB's BoxSampler through
  /// a value accessor, in the grid's index space: X_LU and the grid's world-to-index scale are
  /// composed once per call) and counts them by `rule`, each weighted by area_mm2 (parallel to
  /// samples_U, else std::invalid_argument).
  OpenVdbSampleResult Sample(const std::vector<Eigen::Vector3f>& samples_U,
                             const std::vector<float>& area_mm2, const Eigen::Isometry3d& X_LU,
                             const OpenVdbCountRule& rule) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace occlude::app
