// The OpenVDB half of the peers' module (see bench/peer_module.h and openvdb_peer.h): a
// narrow-band level set of the lower jaw built by OpenVDB's meshToLevelSet and sampled
// trilinearly through a value accessor. OpenVDB's templates are slow to compile; this file
// stays out of the unity batches.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include "bench/peer_module.h"
#include "bench/peers/peer_factories.h"

// OpenVDB's (and the oneTBB, Boost and Imath) headers reach us as system headers, so our
// warning set (-Werror) does not apply to them.
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>

namespace occlude::app::peers {
namespace {

using Sampler =
    openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>;

class OpenVdbGridImpl final : public OpenVdbGrid {
 public:
  OpenVdbGridImpl(const io::TriangleMesh& lower_L, double voxel_mm, int half_width_voxels)
      : voxel_mm_(voxel_mm) {
    CheckPeerMesh(lower_L, "OpenVdbPeer: lower jaw mesh ");
    static std::once_flag initialized;  // OpenVDB's type registry (thread-safe, idempotent)
    std::call_once(initialized, [] { openvdb::initialize(); });
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<openvdb::Vec3s> points;
    points.reserve(lower_L.vertices.size());
    for (const Eigen::Vector3d& v : lower_L.vertices) {
      points.emplace_back(static_cast<float>(v.x()), static_cast<float>(v.y()),
                          static_cast<float>(v.z()));
    }
    std::vector<openvdb::Vec3I> triangles;
    triangles.reserve(lower_L.triangles.size());
    for (const Eigen::Vector3i& t : lower_L.triangles) {
      triangles.emplace_back(static_cast<openvdb::Index32>(t[0]),
                             static_cast<openvdb::Index32>(t[1]),
                             static_cast<openvdb::Index32>(t[2]));
    }
    const openvdb::math::Transform::Ptr xform =
        openvdb::math::Transform::createLinearTransform(voxel_mm);
    grid_ = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(
        *xform, points, triangles, static_cast<float>(half_width_voxels));
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  double build_seconds() const override { return build_seconds_; }
  std::size_t approx_bytes() const override { return static_cast<std::size_t>(grid_->memUsage()); }
  std::size_t active_voxels() const override {
    return static_cast<std::size_t>(grid_->activeVoxelCount());
  }

  double Value(const Eigen::Vector3d& p_L) const override {
    const openvdb::FloatGrid::ConstAccessor accessor = grid_->getConstAccessor();
    const Sampler sampler(accessor, grid_->transform());
    return static_cast<double>(sampler.wsSample(openvdb::Vec3d(p_L.x(), p_L.y(), p_L.z())));
  }

  OpenVdbSampleResult Sample(const std::vector<Eigen::Vector3f>& samples_U,
                             const std::vector<float>& area_mm2, const Eigen::Isometry3d& X_LU,
                             const OpenVdbCountRule& rule) const override {
    if (area_mm2.size() != samples_U.size()) {
      throw std::invalid_argument("OpenVdbPeer::Sample: one area per sample expected");
    }
    const openvdb::FloatGrid& grid = *grid_;
    const openvdb::FloatGrid::ConstAccessor accessor = grid.getConstAccessor();
    const Sampler sampler(accessor, grid.transform());
    // The grid's world-to-index map is the uniform scale 1 / voxel (createLinearTransform, no
    // offset): composed with the pose, one affine map takes U to index space.
    const Eigen::Affine3d X_IU = Eigen::Scaling(1.0 / voxel_mm_) * X_LU;
    // Outside the band the trees hold the background, +-half width: a sample reading it (all
    // eight corners in the background) is unknown, deep inside or far outside.
    const float background = grid.background();
    const double band = rule.contact_band_mm;
    OpenVdbSampleResult result;
    result.samples_evaluated = samples_U.size();
    for (std::size_t i = 0; i < samples_U.size(); ++i) {
      const Eigen::Vector3d p_I = X_IU * samples_U[i].cast<double>();
      const float value = sampler.isSample(openvdb::Vec3d(p_I.x(), p_I.y(), p_I.z()));
      if (value <= -background) {
        ++result.deep_samples;
        continue;
      }
      if (value >= background) continue;
      const auto d = static_cast<double>(value);
      result.min_distance_mm = std::min(result.min_distance_mm, d);
      const auto area = static_cast<double>(area_mm2[i]);
      if (d < 0.0 && -d <= rule.penetration_depth_mm) {
        ++result.penetration_samples;
        result.penetration_area_mm2 += area;
        result.max_penetration_mm = std::max(result.max_penetration_mm, -d);
      } else if (d >= 0.0 && d <= band) {
        ++result.contact_samples;
        result.contact_area_mm2 += area;
      }
    }
    return result;
  }

 private:
  double voxel_mm_ = 0.0;
  double build_seconds_ = 0.0;
  openvdb::FloatGrid::Ptr grid_;
};

}  // namespace

std::unique_ptr<OpenVdbGrid> MakeOpenVdbGrid(const io::TriangleMesh& lower_L, double voxel_mm,
                                             int half_width_voxels) {
  return std::make_unique<OpenVdbGridImpl>(lower_L, voxel_mm, half_width_voxels);
}

}  // namespace occlude::app::peers
