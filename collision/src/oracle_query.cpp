// JawOracle::Query: broad phase (CollectCells on the two sphere trees), then
// the samples of each reported upper cell against the lower's signed distance,
// at the requested accuracy level, accumulated into contact, penetration,
// per-part and regional totals and least-squares residuals.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "oracle_context.h"

namespace occlude::collision {
namespace {

void CheckRequest(const OracleRequest& r) {
  auto bad = [](double v) { return !(v >= 0.0) || !std::isfinite(v); };
  if (bad(r.contact_band_mm))
    throw std::invalid_argument("OracleRequest.contact_band_mm must be finite and >= 0");
  if (bad(r.penetration_search_mm)) {
    throw std::invalid_argument("OracleRequest.penetration_search_mm must be finite and >= 0");
  }
  if (r.residuals && bad(r.residual_band_mm)) {
    throw std::invalid_argument("OracleRequest.residual_band_mm must be finite and >= 0");
  }
  if (!r.pivot_L.allFinite()) throw std::invalid_argument("OracleRequest.pivot_L must be finite");
}

// Reach of the field bound: float rounding of the samples' positions in the
// field's voxels (1e-4 voxel units at the jaws' coordinates is far above it).
constexpr double kFieldBoundSlackMm = 1e-5;

// Distance from the lower surface up to which samples matter: the broad phase
// reports every cell holding such a sample, and the exact level searches this far.
double Reach(const OracleRequest& r) {
  return std::max(
      {r.contact_band_mm, r.penetration_search_mm, r.residuals ? r.residual_band_mm : 0.0});
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
  r->deep_points.clear();
  r->residuals.clear();
  r->cells = r->samples_evaluated = r->node_tests = 0;
}

// Left/right and anterior/posterior shares as fractions of their sums.
void NormalizeShares(OracleResult* result) {
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

}  // namespace

CellRequest JawOracle::BroadPhase(const OracleRequest& request) const {
  CellRequest cells;
  cells.cell_level = options_.cell_level;
  cells.a_level = options_.lower_level;
  cells.distance_bound = options_.distance_bound;
  // A sample within `reach` of the lower surface lies in a reported cell; with
  // the field bound, every sample whose value lies in [-search, outer] lies in
  // one of its voxels.
  const double outer =
      std::max(request.contact_band_mm, request.residuals ? request.residual_band_mm : 0.0);
  const bool field_bound = request.level != AccuracyLevel::kExact && request.cull &&
                           !field_bound_.empty() && outer <= options_.field_bound_mm &&
                           request.penetration_search_mm <= options_.field_bound_depth_mm;
  cells.reach_mm = field_bound ? kFieldBoundSlackMm : Reach(request);
  cells.a_bound = field_bound ? &field_bound_ : nullptr;
  cells.b_spheres = node_sample_sphere_U_.empty() ? nullptr : node_sample_sphere_U_.data();
  return cells;
}

// Each cell is tested at the centre c of its samples' bounding box, r being
// their largest distance from c (QueryContext::Irrelevant; outside the band
// the lower's distance bound stands in for the field). Unknown samples
// (outside the band) are on the centre's side when the centre is unknown
// too and r < band (a segment shorter than the band from a point beyond it
// does not reach the surface), and outside when the centre is known and
// Irrelevant's deep test passes.
bool JawOracle::PrepareCell(std::uint32_t node, std::uint32_t level_begin, QueryContext* q) const {
  const OracleRequest& request = q->request;
  // At voxel level a point's value is the field at its voxel's centre,
  // within 0.866 s of the point: the cell's reach grows by that much.
  const double r = static_cast<double>(cell_radius_[node - level_begin]) +
                   (request.level == AccuracyLevel::kVoxel ? q->interp_error : 0.0);
  const Eigen::Vector3d c_U = cell_center_U_[node - level_begin].cast<double>();
  q->cell_centre_U = cell_center_U_[node - level_begin];
  float d = 0.0f;
  q->cell_known = q->sampler.Value(q->cell.base, q->cell.local, &d);
  q->cell_d = static_cast<double>(d);
  q->cell_r = r;
  if (q->cell_known) {
    if (request.cull && q->Irrelevant(q->cell_d, r)) return false;
    q->unknown_side = q->cell_d > r + q->interp_error - q->band_mm ? UnknownSide::kExterior
                                                                   : UnknownSide::kMaybeInterior;
  } else if (r < q->band_mm) {
    const Eigen::Vector3d c_L = q->X_LU * c_U;
    q->unknown_side = LowerInterior(c_L) ? UnknownSide::kMaybeInterior : UnknownSide::kExterior;
    // Outside, the lower's voxel cubes (which hold its surface) are at least
    // LowerBound away from c, so a sample within r has D >= that - r and its
    // interpolated value (within interp_error of D) is above the outer band.
    if (request.cull && q->unknown_side == UnknownSide::kExterior &&
        lower_.distance_bound().LowerBound(c_L) - r - q->interp_error >
            q->outer + QueryContext::kSlackMm) {
      return false;
    }
  } else {
    q->unknown_side = UnknownSide::kMaybeInterior;
  }
  return true;
}

void JawOracle::Query(const Eigen::Isometry3d& X_LU, const OracleRequest& request,
                      OracleResult* result) const {
  CheckRequest(request);
  Reset(result, request.level, upper_.mesh().parts.size() == 0 ? 1 : upper_.mesh().parts.size());
  for (std::size_t p = 0; p < result->parts.size(); ++p) {
    result->parts[p].part = static_cast<std::int32_t>(p);
    result->parts[p].tooth_number =
        p < upper_.mesh().parts.size() ? upper_.mesh().parts[p].tooth_number : 0;
  }
  thread_local CellResult found;
  CollectCells(lower_, upper_, X_LU, BroadPhase(request), &found);
  result->cells = found.cells_b.size();
  result->node_tests = found.node_tests;
  const int level = std::min(options_.cell_level, upper_.octree().top_level);
  const std::uint32_t level_begin = upper_.octree().level_begin[static_cast<std::size_t>(level)];
  QueryContext q(X_LU, request, sdf_, Reach(request));
  // The cells' grid points first, so that the field's bricks can be asked for
  // some cells ahead (two dependent loads per cell: index entry, then brick).
  thread_local std::vector<SdfSampler::GridPoint> points;
  points.resize(found.cells_b.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = q.sampler.GridPointAt(
        q.A * cell_center_U_[found.cells_b[i] - level_begin].cast<double>() + q.b);
  }
  constexpr std::size_t kIndexAhead = 16,
                        kCornersAhead = 8;  // a-bite-3shape: 8/4 .. 32/16 within noise
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i + kIndexAhead < points.size()) q.sampler.PrefetchIndex(points[i + kIndexAhead]);
    if (i + kCornersAhead < points.size()) q.sampler.PrefetchCorners(points[i + kCornersAhead]);
    const std::uint32_t node = found.cells_b[i];
    if (voxel_sample_begin_[node_leaf_begin_[node]] == voxel_sample_begin_[node_leaf_end_[node]])
      continue;
    q.cell = points[i];
    if (PrepareCell(node, level_begin, &q)) EvaluateCell(node, &q, result);
  }
  if (found.cells_b.empty()) CountNestedPieces(X_LU, result);
  NormalizeShares(result);
}

}  // namespace occlude::collision
