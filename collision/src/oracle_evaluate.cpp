// The evaluation of one upper cell for JawOracle::Query: its samples (or, at
// voxel level, its voxel centroids) against the lower jaw's signed distance,
// accumulated into the result. At sub-voxel level the cell's voxels are culled
// first, each by one field lookup at the centre of its samples:
//
// - a voxel whose centre is known at d is skipped when no sample within r_v of
//   it can count (QueryContext::Irrelevant, the Lipschitz bound);
// - a voxel whose centre is outside the band (unknown) on the exterior side is
//   skipped when r_v < s and the outer band is below (dilation - 1) s: every
//   sample then lies in the centre's voxel or a neighbour (|p - c| < s), whose
//   index is at Chebyshev distance >= dilation from every surface voxel; so the
//   sample is either unknown too (outside, counting for nothing) or in a band
//   voxel at the band's edge, all of whose corners are at least (dilation - 1) s
//   from the surface voxels' cubes, hence from the surface, on the centre's
//   side (no segment between them meets a surface voxel), and a trilinear value
//   lies between its corners' values: above the outer band.
//
// Skipped samples are exactly those that would count for nothing but the
// minimum distance (see OracleResult::min_distance_mm); OracleRequest::cull =
// false evaluates them all.
#include <algorithm>
#include <cmath>
#include <limits>

#include "oracle_context.h"

namespace occlude::collision {

void JawOracle::AddDeep(const Eigen::Vector3d& p_L, double area, std::int32_t part,
                        const OracleRequest& request, OracleResult* result) const {
  ++result->deep_samples;
  if (request.keep_points) {
    result->deep_points.push_back(
        {p_L, -(request.penetration_search_mm + sdf_.band_mm()), area, part});
  }
}

void JawOracle::AddUnknownSample(std::uint32_t i, bool interior, const QueryContext& q,
                                 OracleResult* result) const {
  const Eigen::Vector3d p_L = q.X_LU * sample_p_U_[i].cast<double>();
  const auto area = static_cast<double>(sample_area_[i]);
  if (interior) {
    AddDeep(p_L, area, sample_part_[i], q.request, result);
  } else {
    CountIfDeep(p_L, area, sample_part_[i], q.request, result);
  }
}

void JawOracle::CountIfDeep(const Eigen::Vector3d& p_L, double area, std::int32_t part,
                            const OracleRequest& request, OracleResult* result) const {
  // Outside the measured range: deep inside the lower jaw, or simply far away.
  if (LowerInterior(p_L)) AddDeep(p_L, area, part, request, result);
}

void JawOracle::CountNestedPieces(const Eigen::Isometry3d& X_LU, OracleResult* result) const {
  const VoxelGrid& grid = lower_.grid();
  if (grid.interior_runs.empty() || sample_p_U_.empty()) return;  // no closed lower component
  // Outside the lower grid's box entirely: nothing can be inside.
  const Eigen::Vector3d c_L = X_LU * samples_centre_U_;
  const Eigen::Vector3d box_lo = grid.origin_F,
                        box_hi = grid.origin_F + grid.voxel_size_mm * grid.dims.cast<double>();
  const Eigen::Vector3d gap = (box_lo - c_L).cwiseMax(c_L - box_hi).cwiseMax(0.0);
  if (gap.norm() > samples_radius_) return;
  // No cell was found, so no upper voxel cube (which holds the upper surface) comes within the
  // reach of a lower voxel cube (which holds the lower surface): the surfaces do not meet, and
  // each connected piece of the upper surface lies wholly on one side of the lower surface.
  // One sample tells the side of its piece; a sample outside the lower's surface voxels has its
  // voxel's class.
  for (const ComponentSamples& c : component_samples_) {
    if (LowerInterior(X_LU * sample_p_U_[c.sample].cast<double>())) result->deep_samples += c.count;
  }
}

void JawOracle::Accumulate(const Eigen::Vector3d& p_L, double d, const Eigen::Vector3d& grad,
                           double area, std::int32_t part, const OracleRequest& request,
                           OracleResult* result) const {
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

void JawOracle::EvaluateCell(std::uint32_t node, QueryContext* q, OracleResult* result) const {
  const OracleRequest& request = q->request;
  const bool classify_unknown = q->unknown_side == UnknownSide::kMaybeInterior;
  const std::uint32_t first = node_leaf_begin_[node], last = node_leaf_end_[node];
  if (request.level == AccuracyLevel::kVoxel) {
    // Centroids as float offsets from the cell's centre, into the field's voxel
    // units about the cell's grid point (as the sub-voxel samples); the point in
    // L only for those that count.
    const Eigen::Array4f m0 = q->M.col(0).array(), m1 = q->M.col(1).array(),
                         m2 = q->M.col(2).array();
    for (std::uint32_t v = first; v < last; ++v) {
      if (voxel_area_[v] <= 0.0f) continue;
      ++result->samples_evaluated;
      const Eigen::Vector3f o = voxel_centroid_U_[v] - q->cell_centre_U;
      const Eigen::Array4f local = q->cell.local + m0 * o.x() + m1 * o.y() + m2 * o.z();
      double d = 0.0;
      if (!q->sampler.CellValue(q->cell.base, local, &d)) {
        if (classify_unknown) {
          CountIfDeep(q->X_LU * voxel_centroid_U_[v].cast<double>(),
                      static_cast<double>(voxel_area_[v]), voxel_part_[v], request, result);
        }
        continue;
      }
      result->min_distance_mm = std::min(result->min_distance_mm, d);
      if (d > q->outer) continue;  // counts for nothing else
      Accumulate(q->X_LU * voxel_centroid_U_[v].cast<double>(), d, Eigen::Vector3d::Zero(),
                 static_cast<double>(voxel_area_[v]), voxel_part_[v], request, result);
    }
    return;
  }
  if (request.level == AccuracyLevel::kExact) {
    const std::uint32_t begin = voxel_sample_begin_[first], end = voxel_sample_begin_[last];
    result->samples_evaluated += end - begin;
    for (auto i = begin; i < end; ++i) {
      const Eigen::Vector3d p_L = q->X_LU * sample_p_U_[i].cast<double>();
      SignedDistanceSample s;
      if (!sdf_.Exact(p_L, q->reach, &s)) {
        if (classify_unknown)
          CountIfDeep(p_L, static_cast<double>(sample_area_[i]), sample_part_[i], request, result);
        continue;
      }
      result->min_distance_mm = std::min(result->min_distance_mm, s.distance);
      Accumulate(p_L, s.distance, s.normal, static_cast<double>(sample_area_[i]), sample_part_[i],
                 request, result);
    }
    return;
  }
  EvaluateSubVoxel(first, last, q, result);
}

void JawOracle::EvaluateSubVoxel(std::uint32_t first, std::uint32_t last, QueryContext* q,
                                 OracleResult* result) const {
  const OracleRequest& request = q->request;
  // Voxel tests only pay where enough voxels are skipped: not in a cell whose
  // centre is within half its radius of the outer band (a-bite-3shape at 0.2
  // mm: fewest instructions among thresholds from -1 to +sqrt(3) radii; any
  // threshold gives the same answers).
  constexpr double kTestVoxelsAboveRadii = -0.5;
  const bool test_voxels =
      request.cull && !(q->cell_known && q->cell_d + kTestVoxelsAboveRadii * q->cell_r <= q->outer);
  const bool skip_unknown = q->unknown_side == UnknownSide::kExterior && q->outer < q->band_edge_mm;
  const bool classify_unknown = q->unknown_side == UnknownSide::kMaybeInterior;
  // Samples and voxel centres are offsets from the cell centre, rotated in
  // float into the field's voxel units about the centre's grid point (small
  // numbers, so float loses nothing that matters), then trilinear in the
  // remembered voxel. Local copies stay in registers.
  const SdfSampler::GridPoint c = q->cell;
  const Eigen::Array4f m0 = q->M.col(0).array(), m1 = q->M.col(1).array(), m2 = q->M.col(2).array();
  const float outer = q->outer_float;
  SdfSampler sampler = q->sampler;
  float min_d = std::numeric_limits<float>::infinity();
  std::size_t evaluated = 0;
  for (std::uint32_t v = first; v < last; ++v) {
    const std::uint32_t begin = voxel_sample_begin_[v], end = voxel_sample_begin_[v + 1];
    if (begin == end) continue;
    const Eigen::Vector4f& sphere = voxel_sphere_U_[v];  // centre offset from the cell's, radius
    // The field at the voxel's centre, once looked up (by the voxel test, or
    // for the first unknown sample of a cell whose unknown samples need a side).
    bool centre_looked_up = false, centre_known = false;
    float centre_d = 0.0f;
    auto look_up_centre = [&] {
      const Eigen::Array4f local = c.local + m0 * sphere.x() + m1 * sphere.y() + m2 * sphere.z();
      centre_known = sampler.Value(c.base, local, &centre_d);
      centre_looked_up = true;
    };
    if (test_voxels) {
      look_up_centre();
      if (centre_known) {
        if (q->Irrelevant(static_cast<double>(centre_d), static_cast<double>(sphere.w()))) continue;
      } else if (skip_unknown && static_cast<double>(sphere.w()) < q->s) {
        continue;
      }
    }
    // The side of this voxel's unknown samples: decided once, from the field at
    // the voxel's centre (QueryContext::SideOfUnknown), when the cell left it open.
    UnknownSide voxel_side = q->unknown_side;
    bool voxel_side_found = !classify_unknown;
    evaluated += end - begin;
    for (auto i = begin; i < end; ++i) {
      const Eigen::Vector4f& o = sample_offset_U_[i];
      const Eigen::Array4f local = c.local + m0 * o.x() + m1 * o.y() + m2 * o.z();
      float d = 0.0f;
      if (!sampler.Value(c.base, local, &d)) {
        if (!voxel_side_found) {
          if (!centre_looked_up) look_up_centre();
          voxel_side = q->SideOfUnknown(
              centre_known, static_cast<double>(centre_d), static_cast<double>(sphere.w()), [&] {
                return LowerInterior(q->X_LU *
                                     (q->cell_centre_U + sphere.head<3>()).cast<double>());
              });
          voxel_side_found = true;
        }
        if (voxel_side != UnknownSide::kExterior)
          AddUnknownSample(i, voxel_side == UnknownSide::kInterior, *q, result);
        continue;
      }
      min_d = std::min(min_d, d);
      if (d > outer) continue;  // the common case: counts for nothing else
      Eigen::Vector3f grad = Eigen::Vector3f::Zero();
      if (request.residuals) sampler.ValueAndGradient(c.base, local, &d, &grad);
      Accumulate(q->X_LU * sample_p_U_[i].cast<double>(), static_cast<double>(d),
                 grad.cast<double>(), static_cast<double>(sample_area_[i]), sample_part_[i],
                 request, result);
    }
  }
  result->samples_evaluated += evaluated;
  result->min_distance_mm = std::min(result->min_distance_mm, static_cast<double>(min_d));
  q->sampler = sampler;
}

}  // namespace occlude::collision
