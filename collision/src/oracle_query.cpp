// JawOracle::Query: broad phase (CollectCells on the two sphere trees), then
// the samples of each reported upper cell against the lower's signed distance,
// at the requested accuracy level, accumulated into contact, penetration,
// per-part and regional totals and least-squares residuals.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "occlude/collision/oracle.h"
#include "occlude/collision/sdf_sampler.h"
#include "occlude/collision/sphere_table.h"

namespace occlude::collision {
namespace {

void CheckRequest(const OracleRequest& r) {
  auto bad = [](double v) { return !(v >= 0.0) || !std::isfinite(v); };
  if (bad(r.contact_band_mm)) throw std::invalid_argument("OracleRequest.contact_band_mm must be finite and >= 0");
  if (bad(r.penetration_search_mm)) {
    throw std::invalid_argument("OracleRequest.penetration_search_mm must be finite and >= 0");
  }
  if (r.residuals && bad(r.residual_band_mm)) {
    throw std::invalid_argument("OracleRequest.residual_band_mm must be finite and >= 0");
  }
  if (!r.pivot_L.allFinite()) throw std::invalid_argument("OracleRequest.pivot_L must be finite");
}

// Distance from the lower surface up to which samples matter: the broad phase
// reports every cell holding such a sample, and the exact level searches this far.
double Reach(const OracleRequest& r) {
  return std::max({r.contact_band_mm, r.penetration_search_mm, r.residuals ? r.residual_band_mm : 0.0});
}

void Reset(OracleResult* r, AccuracyLevel level, std::size_t num_parts) {
  r->level = level;
  r->max_penetration_mm = r->penetration_area_mm2 = 0.0;
  r->deepest_p_L.setZero();
  r->deep_samples = 0;
  r->contact_area_mm2 = 0.0;
  r->contact_samples = 0;
  r->min_distance_mm = std::numeric_limits<double>::infinity();
  r->left_share = r->right_share = r->anterior_share = r->posterior_share = 0.0;
  r->parts.assign(num_parts, PartTotals{});
  r->contacts.clear();
  r->penetrations.clear();
  r->residuals.clear();
  r->cells = r->samples_evaluated = r->node_tests = 0;
}

}  // namespace

// Per-query constants shared by the cells of one query.
struct JawOracle::QueryContext {
  const Eigen::Isometry3d& X_LU;
  const OracleRequest& request;
  SdfSampler sampler;
  Eigen::Matrix4f M;  ///< U offsets (mm) -> L voxel units of the field: R_LU / s (top-left 3x3)
  double outer;       ///< samples above this distance count for nothing but the minimum
  SdfSampler::GridPoint cell;  ///< grid point of the current cell's centre in L
  QueryContext(const Eigen::Isometry3d& X, const OracleRequest& r, const NarrowBandSdf& sdf)
      : X_LU(X), request(r), sampler(sdf),
        M(Eigen::Matrix4f::Zero()),
        outer(std::max(r.contact_band_mm, r.residuals ? r.residual_band_mm : 0.0)) {
    M.topLeftCorner<3, 3>() = (X.linear() * (1.0 / sdf.voxel_size_mm())).cast<float>();
  }
};

void JawOracle::CountIfDeep(const Eigen::Vector3d& p_L, OracleResult* result) const {
  // Outside the measured range: deep inside the lower jaw, or simply far away.
  const VoxelGrid& g = lower_.grid();
  if (g.Classify(g.VoxelOf(p_L)) == VoxelClass::kInterior) ++result->deep_samples;
}

void JawOracle::Accumulate(const Eigen::Vector3d& p_L, double d, const Eigen::Vector3d& grad, double area,
                           std::int32_t part, const OracleRequest& request, OracleResult* result) const {
  PartTotals& pt = result->parts[static_cast<std::size_t>(part)];
  if (d < 0.0 && -d <= request.penetration_search_mm + sdf_.band_mm()) {
    result->penetration_area_mm2 += area;
    pt.penetration_area_mm2 += area;
    pt.max_penetration_mm = std::max(pt.max_penetration_mm, -d);
    if (-d > result->max_penetration_mm) {
      result->max_penetration_mm = -d;
      result->deepest_p_L = p_L;
    }
    if (request.keep_points) result->penetrations.push_back({p_L, d, area, part});
  } else if (d >= 0.0 && d <= request.contact_band_mm) {
    result->contact_area_mm2 += area;
    ++result->contact_samples;
    pt.contact_area_mm2 += area;
    ++pt.contact_samples;
    const Eigen::Vector3d rel = p_L - arch_.origin_L;
    (rel.dot(arch_.lateral_L) >= 0.0 ? result->left_share : result->right_share) += area;
    const bool anterior = part_has_tooth_[static_cast<std::size_t>(part)]
                              ? part_is_anterior_tooth_[static_cast<std::size_t>(part)]
                              : rel.dot(arch_.anterior_L) > arch_.anterior_split_mm;
    (anterior ? result->anterior_share : result->posterior_share) += area;
    if (request.keep_points) result->contacts.push_back({p_L, d, area, part});
  }
  if (request.residuals && d <= request.residual_band_mm) {
    DistanceResidual r;
    r.distance_mm = d;
    r.p_L = p_L;
    r.area_mm2 = area;
    const Eigen::Vector3d n = grad.norm() > 0 ? Eigen::Vector3d(grad.normalized()) : grad;
    r.gradient.head<3>() = n.transpose();
    r.gradient.tail<3>() = (p_L - request.pivot_L).cross(n).transpose();
    result->residuals.push_back(r);
  }
}

void JawOracle::EvaluateCell(std::uint32_t node, QueryContext* q, bool may_be_deep, OracleResult* result) const {
  const OracleRequest& request = q->request;
  const std::uint32_t first = node_leaf_begin_[node], last = node_leaf_end_[node];
  if (request.level == AccuracyLevel::kVoxel) {
    for (std::uint32_t v = first; v < last; ++v) {
      if (voxel_area_[v] <= 0.0f) continue;
      ++result->samples_evaluated;
      const Eigen::Vector3d p_L = q->X_LU * voxel_centroid_U_[v].cast<double>();
      const SdfSampler::GridPoint g = q->sampler.GridPointOf(p_L);
      double d = 0.0;
      if (!q->sampler.CellValue(g.base, g.local, &d)) {
        if (may_be_deep) CountIfDeep(p_L, result);
        continue;
      }
      result->min_distance_mm = std::min(result->min_distance_mm, d);
      Accumulate(p_L, d, Eigen::Vector3d::Zero(), static_cast<double>(voxel_area_[v]), voxel_part_[v], request,
                 result);
    }
    return;
  }
  const std::uint32_t begin = voxel_sample_begin_[first], end = voxel_sample_begin_[last];
  result->samples_evaluated += end - begin;
  if (request.level == AccuracyLevel::kExact) {
    for (auto i = begin; i < end; ++i) {
      const Eigen::Vector3d p_L = q->X_LU * sample_p_U_[i].cast<double>();
      SignedDistanceSample s;
      if (!sdf_.Exact(p_L, Reach(request), &s)) {
        if (may_be_deep) CountIfDeep(p_L, result);
        continue;
      }
      result->min_distance_mm = std::min(result->min_distance_mm, s.distance);
      Accumulate(p_L, s.distance, s.normal, static_cast<double>(sample_area_[i]), sample_part_[i], request, result);
    }
    return;
  }
  // Sub-voxel: the samples' offsets from the cell centre, rotated in float into
  // the field's voxel units about the centre's grid point (small numbers, so
  // float loses nothing that matters), then trilinear in the remembered brick.
  const SdfSampler::GridPoint c = q->cell;
  const Eigen::Matrix4f M = q->M;
  const double outer = q->outer;
  SdfSampler sampler = q->sampler;  // a local copy stays in registers
  double min_d = result->min_distance_mm;
  for (auto i = begin; i < end; ++i) {
    const Eigen::Array4f local = c.local + (M * sample_offset_U_[i]).array();
    float df = 0.0f;
    if (!sampler.Value(c.base, local, &df)) {
      if (may_be_deep) CountIfDeep(q->X_LU * sample_p_U_[i].cast<double>(), result);
      continue;
    }
    const double d = static_cast<double>(df);
    min_d = std::min(min_d, d);
    if (d > outer) continue;  // the common case: counts for nothing else
    Eigen::Vector3f grad = Eigen::Vector3f::Zero();
    if (request.residuals) sampler.ValueAndGradient(c.base, local, &df, &grad);
    Accumulate(q->X_LU * sample_p_U_[i].cast<double>(), d, grad.cast<double>(),
               static_cast<double>(sample_area_[i]), sample_part_[i], request, result);
  }
  q->sampler = sampler;
  result->min_distance_mm = min_d;
}

void JawOracle::Query(const Eigen::Isometry3d& X_LU, const OracleRequest& request,
                      OracleResult* result) const {
  CheckRequest(request);
  Reset(result, request.level, upper_.mesh().parts.size() == 0 ? 1 : upper_.mesh().parts.size());
  for (std::size_t p = 0; p < result->parts.size(); ++p) {
    result->parts[p].part = static_cast<std::int32_t>(p);
    result->parts[p].tooth_number = p < upper_.mesh().parts.size() ? upper_.mesh().parts[p].tooth_number : 0;
  }
  CellRequest cells;
  cells.cell_level = options_.cell_level;
  cells.a_level = options_.lower_level;
  cells.distance_bound = options_.distance_bound;
  // A sample within `reach` of the lower surface lies in a reported cell.
  cells.reach_mm = Reach(request);
  thread_local CellResult found;
  CollectCells(lower_, upper_, X_LU, cells, &found);
  result->cells = found.cells_b.size();
  result->node_tests = found.node_tests;
  // A cell is tested at the centre c of its samples' bounding box, r being
  // their largest distance from c. The interpolated field is the trilinear
  // interpolant of exact (1-Lipschitz) grid values, so each partial derivative
  // is at most 1 in size: interp(p) >= interp(c) - |p - c|_1 >= interp(c) -
  // sqrt(3) r. A cell with interp(c) above the outer band by sqrt(3) r holds
  // no sample of interest (samples only count outside up to the contact band,
  // or the residual band). The old bound, interp(c) above r + outer + 2 * 0.866
  // s (interpolation error 0.866 s at c and at the sample), is kept when smaller.
  const int level = std::min(options_.cell_level, upper_.octree().top_level);
  const std::uint32_t level_begin = upper_.octree().level_begin[static_cast<std::size_t>(level)];
  const double outer = std::max(request.contact_band_mm, request.residuals ? request.residual_band_mm : 0.0);
  const double interp_error = kCubeCircumradius * sdf_.voxel_size_mm();
  constexpr double kSqrt3 = 1.7320508075688772;
  constexpr double kSlackMm = 1e-6;  // float rounding of the stored values
  QueryContext q(X_LU, request, sdf_);
  for (const std::uint32_t node : found.cells_b) {
    if (voxel_sample_begin_[node_leaf_begin_[node]] == voxel_sample_begin_[node_leaf_end_[node]]) continue;
    const double r = static_cast<double>(cell_radius_[node - level_begin]);
    const Eigen::Vector3d c_L = X_LU * cell_center_U_[node - level_begin].cast<double>();
    q.cell = q.sampler.GridPointOf(c_L);
    float df = 0.0f;
    const bool known = q.sampler.Value(q.cell.base, q.cell.local, &df);
    const double d = static_cast<double>(df);
    if (known && d > outer + std::min(kSqrt3 * r, r + 2.0 * interp_error) + kSlackMm) continue;
    // A centre known to be at d > -band + r + 0.866 s has every sample within
    // the band or outside it (same Lipschitz argument): none is deep. A centre
    // beyond the band is farther than band_mm from the surface, so every
    // sample (within r, below band_mm) is on the centre's side.
    const bool may_be_deep =
        known ? d <= r + interp_error - sdf_.band_mm()
              : lower_.grid().Classify(lower_.grid().VoxelOf(c_L)) == VoxelClass::kInterior;
    EvaluateCell(node, &q, may_be_deep, result);
  }

  const double lr = result->left_share + result->right_share;
  const double ap = result->anterior_share + result->posterior_share;
  if (lr > 0) {
    result->left_share /= lr;
    result->right_share /= lr;
  }
  if (ap > 0) {
    result->anterior_share /= ap;
    result->posterior_share /= ap;
  }
}

}  // namespace occlude::collision
