// PoseEvaluation from one oracle query; the outlier-robust penetration
// measure; the occlusal pivot, reference points and pose errors.
#include "occlude/planner/evaluation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "occlude/angles.h"
#include "occlude/collision/arch_frame.h"

namespace occlude::planner {

double OutlierBudget(const PlanRequest& request, double near_contact_area_mm2) {
  switch (request.penetration_measure) {
    case PenetrationMeasure::kMax:
      return 0.0;
    case PenetrationMeasure::kOutlierArea:
      return request.outlier_area_mm2;
    case PenetrationMeasure::kPercentile:
      return (100.0 - request.penetration_percentile) / 100.0 * near_contact_area_mm2;
  }
  return 0.0;
}

double SpikePatchCap(const PlanRequest& request) {
  return request.penetration_measure == PenetrationMeasure::kMax ? 0.0
                                                                 : request.spike_patch_max_mm2;
}

double SpikeShallowMm(const PlanRequest& request) {
  return std::max(
      0.002, 0.5 * std::min(request.max_penetration_mm, request.seat_penetration_allowance_mm));
}

double RobustPenetration(const std::vector<std::pair<double, double>>& depth_area, std::size_t deep,
                         double deep_depth_mm, double deep_area_mm2, double outlier_budget_mm2,
                         std::vector<std::size_t>* outlier_index) {
  if (outlier_index) outlier_index->clear();
  double budget = outlier_budget_mm2;
  // Deep (unmeasured) samples are the deepest of all: they go first.
  if (deep > 0) {
    const double deep_total = static_cast<double>(deep) * deep_area_mm2;
    if (deep_total > budget) return deep_depth_mm;
    budget -= deep_total;
  }
  std::vector<std::size_t> order(depth_area.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return depth_area[a].first > depth_area[b].first ||
           (depth_area[a].first == depth_area[b].first && a < b);
  });
  for (const std::size_t i : order) {
    if (depth_area[i].second > budget) return depth_area[i].first;
    budget -= depth_area[i].second;
    if (outlier_index) outlier_index->push_back(i);
  }
  return 0.0;
}

PoseEvaluation EvaluatePose(const OracleStage& stage, const Eigen::Isometry3d& X_LU,
                            const PlanRequest& request) {
  collision::OracleRequest q;
  q.level = stage.level;
  q.contact_band_mm = request.contact_band_mm;
  q.penetration_search_mm = std::max(0.3, 4.0 * request.max_penetration_mm);
  q.keep_points = true;
  collision::OracleResult r;
  stage.oracle->Query(X_LU, q, &r);

  PoseEvaluation e;
  e.contact_area_mm2 = r.contact_area_mm2;
  e.contact_samples = r.contact_samples;
  e.max_penetration_mm = r.max_penetration_mm;
  e.penetration_area_mm2 = r.penetration_area_mm2;
  e.deep_samples = r.deep_samples;
  e.left_share = r.left_share;
  e.right_share = r.right_share;
  e.anterior_share = r.anterior_share;
  e.posterior_share = r.posterior_share;
  e.parts = r.parts;
  // Spike patches first (linked at 2.5 sample spacings), then the deepest-area budget. The
  // deep samples the oracle lists join the patches at the depth they are at least at, as
  // EvaluateSet's do: the tip of a spike pressed beyond the measured depth stays a spike.
  const double deep_depth = q.penetration_search_mm + stage.oracle->lower_sdf().band_mm();
  std::vector<PenetratingSample> pen;
  pen.reserve(r.penetrations.size() + r.deep_points.size());
  for (const auto& p : r.penetrations) pen.push_back({p.p_L, -p.distance_mm, p.area_mm2});
  for (const auto& p : r.deep_points) pen.push_back({p.p_L, deep_depth, p.area_mm2});
  const std::vector<bool> spike =
      SpikeMembersForMeasure(pen, 2.5 * stage.oracle->sample_spacing_mm(), SpikePatchCap(request),
                             request.max_penetration_mm, SpikeShallowMm(request));
  const std::size_t measured = r.penetrations.size();
  auto point = [&r, measured](std::size_t i) -> const collision::SurfacePoint& {
    return i < measured ? r.penetrations[i] : r.deep_points[i - measured];
  };
  std::vector<std::pair<double, double>> depth_area;
  std::vector<std::size_t> kept;
  std::size_t deep_spikes = 0;
  for (std::size_t i = 0; i < pen.size(); ++i) {
    if (spike[i]) {
      const auto& p = point(i);
      e.outliers.push_back({p.p_L, pen[i].depth_mm, p.area_mm2, p.part, true});
      deep_spikes += i >= measured ? 1 : 0;
      continue;
    }
    if (i < measured) {  // the deep ones that are no spike stay counted as deep
      depth_area.emplace_back(pen[i].depth_mm, pen[i].area_mm2);
      kept.push_back(i);
    }
  }
  const double mean_area =
      r.penetrations.empty() ? 0.1
                             : r.penetration_area_mm2 / static_cast<double>(r.penetrations.size());
  std::vector<std::size_t> outliers;
  e.constrained_penetration_mm = RobustPenetration(
      depth_area, r.deep_samples - deep_spikes, deep_depth, mean_area,
      OutlierBudget(request, r.contact_area_mm2 + r.penetration_area_mm2), &outliers);
  if (r.deep_samples > 0) e.max_penetration_mm = std::max(e.max_penetration_mm, deep_depth);
  for (const std::size_t k : outliers) {
    const auto& p = r.penetrations[kept[k]];
    e.outliers.push_back({p.p_L, -p.distance_mm, p.area_mm2, p.part, false});
  }
  // Posterior contact per side, for the bilateral weighting.
  const collision::ArchFrame& arch = stage.oracle->arch();
  for (const auto& c : r.contacts) {
    const Eigen::Vector3d rel = c.p_L - arch.origin_L;
    if (rel.dot(arch.anterior_L) > arch.anterior_split_mm) continue;
    (rel.dot(arch.lateral_L) >= 0.0 ? e.posterior_left_mm2 : e.posterior_right_mm2) += c.area_mm2;
  }
  e.score = e.contact_area_mm2 - request.bilateral_posterior_weight *
                                     std::abs(e.posterior_left_mm2 - e.posterior_right_mm2);
  e.feasible = e.constrained_penetration_mm <= request.max_penetration_mm + 1e-9;
  return e;
}

namespace {

// Occlusal-facing triangles of the upper within the crown depth, in L.
template <typename Visit>
void ForOcclusalTriangles(const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU,
                          const Eigen::Vector3d& occlusal_L, double crown_depth_mm, Visit visit) {
  const Eigen::Vector3d down = -occlusal_L.normalized();
  double lowest = -std::numeric_limits<double>::infinity();
  for (const auto& v : upper_U.vertices) lowest = std::max(lowest, (X_LU * v).dot(down));
  for (std::size_t t = 0; t < upper_U.num_triangles(); ++t) {
    const Eigen::Vector3d a = X_LU * upper_U.corner(t, 0), b = X_LU * upper_U.corner(t, 1),
                          c = X_LU * upper_U.corner(t, 2);
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double area2 = n.norm();
    if (area2 <= 0.0 || n.dot(down) / area2 <= 0.5) continue;
    const Eigen::Vector3d centroid = (a + b + c) / 3.0;
    if (lowest - centroid.dot(down) > crown_depth_mm) continue;
    visit(centroid, 0.5 * area2);
  }
}

}  // namespace

std::vector<Eigen::Vector3d> ArchReferencePoints_U(const io::TriangleMesh& upper_U,
                                                   const Eigen::Isometry3d& X_LU,
                                                   const collision::ArchFrame& arch) {
  const Eigen::Vector3d pivot_L = collision::UpperOcclusalCentre(upper_U, X_LU, arch.occlusal_L);
  Eigen::Vector3d front = pivot_L, back_left = pivot_L, back_right = pivot_L;
  double best_front = -1e300, best_left = -1e300, best_right = -1e300;
  ForOcclusalTriangles(upper_U, X_LU, arch.occlusal_L, 4.0, [&](const Eigen::Vector3d& c, double) {
    const Eigen::Vector3d rel = c - pivot_L;
    const double ant = rel.dot(arch.anterior_L), lat = rel.dot(arch.lateral_L);
    if (ant > best_front) best_front = ant, front = c;
    // Molars: far back and to the side (45 degrees between posterior and lateral).
    if (-ant + lat > best_left) best_left = -ant + lat, back_left = c;
    if (-ant - lat > best_right) best_right = -ant - lat, back_right = c;
  });
  const Eigen::Isometry3d X_UL = X_LU.inverse();
  return {X_UL * pivot_L, X_UL * front, X_UL * back_left, X_UL * back_right};
}

PoseError ComparePoses(const Eigen::Isometry3d& X_LU_a, const Eigen::Isometry3d& X_LU_b,
                       const std::vector<Eigen::Vector3d>& points_U) {
  PoseError e;
  for (const auto& p : points_U)
    e.translation_mm = std::max(e.translation_mm, (X_LU_a * p - X_LU_b * p).norm());
  const Eigen::AngleAxisd aa(Eigen::Matrix3d(X_LU_a.linear() * X_LU_b.linear().transpose()));
  e.rotation_deg = DegreesFromRadians(std::abs(aa.angle()));
  return e;
}

std::vector<PathPoint> EvaluatePath(const OracleStage& stage, const Eigen::Isometry3d& X_LU_from,
                                    const Eigen::Isometry3d& X_LU_to,
                                    const Eigen::Vector3d& p_LPivot,
                                    const std::vector<Eigen::Vector3d>& points_U,
                                    const PlanRequest& request, int steps) {
  if (steps < 1) {
    throw std::invalid_argument("EvaluatePath: steps must be at least 1 (got " +
                                std::to_string(steps) + ")");
  }
  const PoseParameters to = DecomposePose(X_LU_to, p_LPivot, X_LU_from);
  std::vector<PathPoint> path;
  path.reserve(static_cast<std::size_t>(steps) + 1);
  for (int k = 0; k <= steps; ++k) {
    PathPoint p;
    p.s = static_cast<double>(k) / steps;
    PoseParameters at;
    at.translation_mm = p.s * to.translation_mm;
    at.rotation_deg = p.s * to.rotation_deg;
    p.X_LU = k == steps ? X_LU_to : ComposePose(at, p_LPivot, X_LU_from);
    p.from_start = ComparePoses(p.X_LU, X_LU_from, points_U);
    p.evaluation = EvaluatePose(stage, p.X_LU, request);
    path.push_back(std::move(p));
  }
  return path;
}

bool Dominates(const PoseEvaluation& a, const PoseEvaluation& b) {
  return a.contact_area_mm2 > b.contact_area_mm2 &&
         a.constrained_penetration_mm <= b.constrained_penetration_mm &&
         a.deep_samples <= b.deep_samples;
}

}  // namespace occlude::planner
