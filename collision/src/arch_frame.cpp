// The arch frame estimated from the two jaws in a common frame (the bite as
// given): the occlusal axis is the normal of the plane fitted (least squares,
// smallest principal axis) through the interface, the lower vertices within
// kInterfaceMm of an upper vertex, oriented lower -> upper; without enough
// interface (jaws apart) the smallest principal axis of the lower jaw. The
// lateral direction is the widest spread of the lower arch across that axis,
// and anterior the direction in which the arch narrows (the incisors). The centre of the
// upper occlusal surface (see arch_frame.h).
#include "occlude/collision/arch_frame.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace occlude::collision {
namespace {

constexpr double kInterfaceMm = 1.5;  // lower vertices this close to the upper form the interface
constexpr std::size_t kMinInterface = 30;  // fewer: fall back to the lower jaw's own shape

Eigen::Vector3d Centroid(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& v : points) c += v;
  return points.empty() ? c : Eigen::Vector3d(c / static_cast<double>(points.size()));
}

// Unit eigenvector of the smallest eigenvalue of the points' covariance.
Eigen::Vector3d SmallestAxis(const std::vector<Eigen::Vector3d>& points) {
  const Eigen::Vector3d c = Centroid(points);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& v : points) cov += (v - c) * (v - c).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  return eig.eigenvectors().col(0).normalized();
}

std::uint64_t CellKey(const Eigen::Vector3d& p, double cell) {
  auto u = [&](double v) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / cell)) + (1 << 20)) &
           0x1fffff;
  };
  return (u(p.x()) << 42) | (u(p.y()) << 21) | u(p.z());
}

// Lower vertices with an upper vertex within kInterfaceMm (grid of upper vertices; the test
// is on vertices, so a coarse upper mesh widens the interface slightly: it only feeds a fit).
std::vector<Eigen::Vector3d> InterfacePoints(const io::TriangleMesh& lower_L,
                                             const io::TriangleMesh& upper_L) {
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  for (std::uint32_t i = 0; i < upper_L.vertices.size(); ++i)
    cells[CellKey(upper_L.vertices[i], kInterfaceMm)].push_back(i);
  std::vector<Eigen::Vector3d> out;
  const double r2 = kInterfaceMm * kInterfaceMm;
  for (const auto& v : lower_L.vertices) {
    bool near = false;
    for (int d = 0; d < 27 && !near; ++d) {
      const Eigen::Vector3d q =
          v + kInterfaceMm * Eigen::Vector3i(d % 3 - 1, (d / 3) % 3 - 1, d / 9 - 1).cast<double>();
      const auto it = cells.find(CellKey(q, kInterfaceMm));
      if (it == cells.end()) continue;
      for (const std::uint32_t j : it->second) {
        if ((upper_L.vertices[j] - v).squaredNorm() <= r2) {
          near = true;
          break;
        }
      }
    }
    if (near) out.push_back(v);
  }
  return out;
}

}  // namespace

ArchFrame EstimateArchFrame(const io::TriangleMesh& lower_L, const io::TriangleMesh& upper_L) {
  ArchFrame f;
  f.origin_L = Centroid(lower_L.vertices);
  const Eigen::Vector3d towards_upper = Centroid(upper_L.vertices) - f.origin_L;
  const std::vector<Eigen::Vector3d> interface = InterfacePoints(lower_L, upper_L);
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();
  if (interface.size() >= kMinInterface) {
    axis = SmallestAxis(interface);
  } else if (lower_L.vertices.size() >= 3) {
    axis = SmallestAxis(lower_L.vertices);
  } else if (towards_upper.norm() > 0.0) {
    axis = towards_upper.normalized();
  }
  if (!axis.allFinite() || axis.norm() < 0.5) axis = Eigen::Vector3d::UnitY();
  if (axis.dot(towards_upper) < 0.0) axis = -axis;
  f.occlusal_L = axis.normalized();
  // Horizontal covariance of the lower arch.
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - f.occlusal_L * f.occlusal_L.transpose();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& v : lower_L.vertices) {
    const Eigen::Vector3d h = P * (v - f.origin_L);
    cov += h * h.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d widest = eig.eigenvectors().col(2);
  Eigen::Vector3d depth = f.occlusal_L.cross(widest).normalized();
  // The incisors are where the arch is narrow: compare the spread across the
  // arch in the two halves along `depth`.
  double spread[2] = {0, 0}, count[2] = {0, 0};
  double lo = 0, hi = 0;
  for (const auto& v : lower_L.vertices) {
    const double a = (v - f.origin_L).dot(depth);
    const int half = a > 0 ? 1 : 0;
    spread[half] += std::abs((v - f.origin_L).dot(widest));
    count[half] += 1;
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
  const bool flip = count[0] > 0 && count[1] > 0 && spread[1] / count[1] > spread[0] / count[0];
  if (flip) {
    depth = -depth;
    std::swap(lo, hi);
    lo = -lo;
    hi = -hi;
  }
  f.anterior_L = depth;
  f.lateral_L = f.occlusal_L.cross(f.anterior_L).normalized();
  f.anterior_split_mm = hi - 0.35 * (hi - lo);
  return f;
}

Eigen::Vector3d UpperOcclusalCentre(const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU,
                                    const Eigen::Vector3d& occlusal_L) {
  if (upper_U.vertices.empty()) return Eigen::Vector3d::Zero();
  std::vector<double> heights;
  heights.reserve(upper_U.vertices.size());
  Eigen::AlignedBox3d box;  // constructed empty
  for (const auto& v : upper_U.vertices) {
    const Eigen::Vector3d p_L = X_LU * v;
    heights.push_back(p_L.dot(occlusal_L));
    box.extend(p_L);
  }
  const std::size_t k = heights.size() / 20;
  std::nth_element(heights.begin(), heights.begin() + static_cast<std::ptrdiff_t>(k),
                   heights.end());
  const double level = heights[k];
  const Eigen::Vector3d c = box.center();
  return c + (level - c.dot(occlusal_L)) * occlusal_L;
}

}  // namespace occlude::collision
