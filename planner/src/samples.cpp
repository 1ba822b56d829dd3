// The occlusal sample set: the upper surface that can touch the lower,
// subdivided and clustered on a grid so that each stage evaluates no more
// points than its resolution needs; and the signed distance at a stage.
#include <algorithm>
#include <cmath>
#include <ctime>
#include <unordered_map>
#include <vector>

#include "occlude/clock.h"
#include "occlude/collision/floor_int.h"
#include "search_internal.h"

namespace occlude::planner::detail {

double CpuSeconds() { return ThreadCpuSeconds(); }

InnerBudget& CurrentInnerBudget() {
  thread_local InnerBudget budget;
  return budget;
}

namespace {

struct Cluster {
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // area-weighted
  double area = 0.0;
  std::int32_t part = 0;
};

std::uint64_t CellKey(const Eigen::Vector3d& p, double spacing) {
  auto c = [&](double v) {
    return static_cast<std::uint64_t>(collision::detail::FloorInt64(v / spacing) + (1 << 20)) &
           0x1fffff;
  };
  return (c(p.x()) << 42) | (c(p.y()) << 21) | c(p.z());
}

}  // namespace

SampleSet OcclusalSamples(const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU,
                          const Eigen::Vector3d& occlusal_L, double spacing_mm,
                          double crown_depth_mm) {
  const Eigen::Vector3d down_U = -(X_LU.linear().transpose() * occlusal_L).normalized();
  double lowest = -1e300;
  for (const auto& v : upper_U.vertices) lowest = std::max(lowest, v.dot(down_U));
  // The clusters in the order of their first sample (a deterministic output order), and where
  // each cell's cluster is.
  std::vector<Cluster> clusters;
  std::unordered_map<std::uint64_t, std::uint32_t> cell_cluster;
  cell_cluster.reserve(upper_U.num_triangles() / 2);
  for (std::size_t t = 0; t < upper_U.num_triangles(); ++t) {
    const Eigen::Vector3d a = upper_U.corner(t, 0), b = upper_U.corner(t, 1),
                          c = upper_U.corner(t, 2);
    if (lowest - (a + b + c).dot(down_U) / 3.0 > crown_depth_mm) continue;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double n_norm = n.norm();
    const Eigen::Vector3d unit_n = n.normalized();
    if (n_norm <= 0.0 || unit_n.dot(down_U) < -0.3) continue;
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int k = std::max(1, static_cast<int>(std::ceil(longest / spacing_mm)));
    const double area = 0.5 * n_norm / (k * k);
    const Eigen::Vector3d u = (b - a) / k, w = (c - a) / k;
    auto add = [&](const Eigen::Vector3d& p) {
      const auto [at, added] = cell_cluster.try_emplace(
          CellKey(p, spacing_mm), static_cast<std::uint32_t>(clusters.size()));
      if (added) {
        clusters.emplace_back();
        clusters.back().part = upper_U.triangle_part.empty() ? 0 : upper_U.triangle_part[t];
      }
      Cluster& cl = clusters[at->second];
      cl.weighted += area * p;
      cl.normal += area * unit_n;
      cl.area += area;
    };
    for (int i = 0; i < k; ++i) {
      for (int j = 0; i + j < k; ++j) {
        const Eigen::Vector3d o = a + i * u + j * w;
        add(o + (u + w) / 3.0);
        if (i + j < k - 1) add(o + 2.0 * (u + w) / 3.0);
      }
    }
  }
  SampleSet set;
  set.spacing_mm = spacing_mm;
  for (const Cluster& cl : clusters) {
    set.p_U.push_back(cl.weighted / cl.area);
    set.area_mm2.push_back(cl.area);
    set.part.push_back(cl.part);
    const double nn = cl.normal.norm();
    set.facing.push_back(nn > 0.0 ? cl.normal.dot(down_U) / nn : 0.0);
  }
  return set;
}

double StageSpacing(const OracleStage& stage) {
  return std::clamp(0.6 * stage.oracle->lower_sdf().voxel_size_mm(), 0.25, 0.6);
}

bool StageDistance(const OracleStage& stage, const Eigen::Vector3d& p_L, double reach_mm, double* d,
                   Eigen::Vector3d* gradient, bool* deep) {
  const collision::JawOracle& oracle = *stage.oracle;
  bool known = false;
  if (stage.level == collision::AccuracyLevel::kExact) {
    collision::SignedDistanceSample s;
    known = oracle.lower_sdf().Exact(p_L, reach_mm, &s);
    if (known) {
      *d = s.distance;
      if (gradient) *gradient = s.normal;
    }
  } else {
    // The interpolant's own derivative (about unit length), so that Jacobians are exact for
    // the distances they differentiate (the oracle's residuals normalize it).
    Eigen::Vector3d g;
    known = oracle.lower_sdf().Interpolate(p_L, d, &g);
    if (known && gradient) *gradient = g;
  }
  *deep = !known && oracle.LowerInterior(p_L);
  return known;
}

}  // namespace occlude::planner::detail
