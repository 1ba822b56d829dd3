// The OpenVDB peer (see openvdb_peer.h): a narrow-band level set of the lower jaw built by
// OpenVDB's meshToLevelSet and sampled trilinearly through a value accessor. Everything that
// touches OpenVDB is inside OCCLUDE_HAVE_OPENVDB and in this one translation unit (its
// templates are slow to compile; the file stays out of the unity batches); without it, a stub
// whose Available() is false and whose other members throw.
#include "bench/openvdb_peer.h"

#include <stdexcept>
#include <string>

#ifdef OCCLUDE_HAVE_OPENVDB

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

// OpenVDB's (and the oneTBB, Boost and Imath) headers reach us as system headers, so our
// warning set (-Werror) does not apply to them.
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>

namespace occlude::app {
namespace {

void CheckMesh(const io::TriangleMesh& mesh) {
  const std::string prefix = "OpenVdbPeer: lower jaw mesh ";
  if (mesh.triangles.empty()) throw std::invalid_argument(prefix + "has no triangles");
  const auto nv = static_cast<int>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    if ((tri.array() < 0).any() || (tri.array() >= nv).any()) {
      throw std::invalid_argument(prefix + "triangle " + std::to_string(t) +
                                  " indexes a vertex outside 0.." + std::to_string(nv - 1));
    }
  }
}

using Sampler =
    openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>;

}  // namespace

struct OpenVdbPeer::Impl {
  double voxel_mm = 0.0;
  int half_width_voxels = 0;
  double build_seconds = 0.0;
  openvdb::FloatGrid::Ptr grid;
};

bool OpenVdbPeer::Available() { return true; }

OpenVdbPeer::OpenVdbPeer(const io::TriangleMesh& lower_L, double voxel_mm, int half_width_voxels)
    : impl_(std::make_unique<Impl>()) {
  if (!(voxel_mm > 0.0) || !std::isfinite(voxel_mm)) {
    throw std::invalid_argument("OpenVdbPeer: the voxel size must be finite and > 0 mm");
  }
  if (half_width_voxels < 1) {
    throw std::invalid_argument("OpenVdbPeer: the band's half width must be at least 1 voxel");
  }
  CheckMesh(lower_L);
  static std::once_flag initialized;  // OpenVDB's type registry (thread-safe, idempotent)
  std::call_once(initialized, [] { openvdb::initialize(); });
  impl_->voxel_mm = voxel_mm;
  impl_->half_width_voxels = half_width_voxels;
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
    triangles.emplace_back(static_cast<openvdb::Index32>(t[0]), static_cast<openvdb::Index32>(t[1]),
                           static_cast<openvdb::Index32>(t[2]));
  }
  const openvdb::math::Transform::Ptr xform =
      openvdb::math::Transform::createLinearTransform(voxel_mm);
  impl_->grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(
      *xform, points, triangles, static_cast<float>(half_width_voxels));
  impl_->build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

OpenVdbPeer::~OpenVdbPeer() = default;
OpenVdbPeer::OpenVdbPeer(OpenVdbPeer&& other) noexcept = default;
OpenVdbPeer& OpenVdbPeer::operator=(OpenVdbPeer&& other) noexcept = default;

double OpenVdbPeer::voxel_mm() const { return impl_->voxel_mm; }
int OpenVdbPeer::half_width_voxels() const { return impl_->half_width_voxels; }
double OpenVdbPeer::build_seconds() const { return impl_->build_seconds; }
std::size_t OpenVdbPeer::approx_bytes() const {
  return static_cast<std::size_t>(impl_->grid->memUsage());
}
std::size_t OpenVdbPeer::active_voxels() const {
  return static_cast<std::size_t>(impl_->grid->activeVoxelCount());
}

double OpenVdbPeer::Value(const Eigen::Vector3d& p_L) const {
  const openvdb::FloatGrid::ConstAccessor accessor = impl_->grid->getConstAccessor();
  const Sampler sampler(accessor, impl_->grid->transform());
  return static_cast<double>(sampler.wsSample(openvdb::Vec3d(p_L.x(), p_L.y(), p_L.z())));
}

OpenVdbSampleResult OpenVdbPeer::Sample(const std::vector<Eigen::Vector3f>& samples_U,
                                        const std::vector<float>& area_mm2,
                                        const Eigen::Isometry3d& X_LU,
                                        const OpenVdbCountRule& rule) const {
  if (area_mm2.size() != samples_U.size()) {
    throw std::invalid_argument("OpenVdbPeer::Sample: one area per sample expected");
  }
  const openvdb::FloatGrid& grid = *impl_->grid;
  const openvdb::FloatGrid::ConstAccessor accessor = grid.getConstAccessor();
  const Sampler sampler(accessor, grid.transform());
  // The grid's world-to-index map is the uniform scale 1 / voxel (createLinearTransform, no
  // offset): composed with the pose, one affine map takes U to index space.
  const Eigen::Affine3d X_IU = Eigen::Scaling(1.0 / impl_->voxel_mm) * X_LU;
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

}  // namespace occlude::app

#else  // !OCCLUDE_HAVE_OPENVDB

namespace occlude::app {
namespace {
[[noreturn]] void ThrowNoOpenVdb() {
  throw std::runtime_error(
      "occlude was built without OpenVDB (apt-get install libopenvdb-dev libboost-dev)");
}
}  // namespace

struct OpenVdbPeer::Impl {};

bool OpenVdbPeer::Available() { return false; }

OpenVdbPeer::OpenVdbPeer(const io::TriangleMesh& /*lower_L*/, double /*voxel_mm*/,
                         int /*half_width_voxels*/) {
  ThrowNoOpenVdb();
}
OpenVdbPeer::~OpenVdbPeer() = default;
OpenVdbPeer::OpenVdbPeer(OpenVdbPeer&& other) noexcept = default;
OpenVdbPeer& OpenVdbPeer::operator=(OpenVdbPeer&& other) noexcept = default;

double OpenVdbPeer::voxel_mm() const { ThrowNoOpenVdb(); }
int OpenVdbPeer::half_width_voxels() const { ThrowNoOpenVdb(); }
double OpenVdbPeer::build_seconds() const { ThrowNoOpenVdb(); }
std::size_t OpenVdbPeer::approx_bytes() const { ThrowNoOpenVdb(); }
std::size_t OpenVdbPeer::active_voxels() const { ThrowNoOpenVdb(); }
double OpenVdbPeer::Value(const Eigen::Vector3d& /*p_L*/) const { ThrowNoOpenVdb(); }
OpenVdbSampleResult OpenVdbPeer::Sample(const std::vector<Eigen::Vector3f>& /*samples_U*/,
                                        const std::vector<float>& /*area_mm2*/,
                                        const Eigen::Isometry3d& /*X_LU*/,
                                        const OpenVdbCountRule& /*rule*/) const {
  ThrowNoOpenVdb();
}

}  // namespace occlude::app

#endif  // OCCLUDE_HAVE_OPENVDB
