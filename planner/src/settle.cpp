// The fast objective on a sample set (smooth contact score, robust
// penetration) and the settle: a bracketing search along the occlusal axis for
// the pose where the penetration measure just meets its limit.
#include <algorithm>
#include <cmath>
#include <limits>

#include "search_internal.h"

namespace occlude::planner::detail {

ResidualSettings SeatSettings(const OracleStage& stage, const PlanRequest& request) {
  ResidualSettings s;
  s.contact_band_mm = request.contact_band_mm;
  s.penetration_allowance_mm = request.seat_penetration_allowance_mm;
  s.attraction_scale_mm = request.seat_scale_mm;
  s.attraction_min_facing = request.seat_min_facing;
  // Distances are known within the field's band only. A wide (coarse) field gets a window
  // and a Cauchy scale that grow with it, so that far samples still pull.
  const double band = stage.oracle->lower_sdf().band_mm();
  s.window_mm = std::min(std::max(request.seat_window_mm, 0.8 * band), band);
  s.attraction_scale_mm = std::max(request.seat_scale_mm, s.window_mm / 3.0);
  s.range_mm = s.window_mm;
  return s;
}

namespace {

// Pass 1 of EvaluateSet: per sample its signed distance (unknown: -band when deep in the lower,
// else the seat window), whether it is known and deep, and the penetrating samples.
struct SetDistances {
  std::vector<double> dist;
  std::vector<char> known, deep;
  std::vector<PenetratingSample> pen;
  std::vector<std::size_t> pen_index;
};

SetDistances MeasureSet(const OracleStage& stage, const SampleSet& samples,
                        const Eigen::Isometry3d& X_LU, double reach_mm, double window_mm) {
  const double deep_distance = -stage.oracle->lower_sdf().band_mm();
  const std::size_t n = samples.size();
  SetDistances m;
  m.dist.resize(n);
  m.known.resize(n);
  m.deep.resize(n);
  ForBlocks(n, kSamplesPerBlock, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      bool is_deep = false;
      const bool known =
          StageDistance(stage, X_LU * samples.p_U[i], reach_mm, &m.dist[i], nullptr, &is_deep);
      m.known[i] = known ? 1 : 0;
      m.deep[i] = is_deep ? 1 : 0;
      if (!m.known[i]) m.dist[i] = is_deep ? deep_distance : window_mm;
    }
  });
  for (std::size_t i = 0; i < n; ++i) {
    if (m.known[i] ? m.dist[i] < 0.0 : m.deep[i] != 0) {
      m.pen.push_back({X_LU * samples.p_U[i], -m.dist[i], samples.area_mm2[i]});
      m.pen_index.push_back(i);
    }
  }
  return m;
}

// Per sample: a member of a spike patch among the penetrating samples of `m`.
std::vector<char> SpikeFlags(const SetDistances& m, const SampleSet& samples,
                             const PlanRequest& req) {
  std::vector<char> spike(samples.size(), 0);
  if (m.pen.empty()) return spike;
  const std::vector<bool> member =
      SpikeMembersForMeasure(m.pen, 2.5 * samples.spacing_mm, SpikePatchCap(req),
                             req.max_penetration_mm, SpikeShallowMm(req));
  for (std::size_t k = 0; k < m.pen.size(); ++k) spike[m.pen_index[k]] = member[k] ? 1 : 0;
  return spike;
}

}  // namespace

std::vector<bool> SpikeSamples(const OracleStage& stage, const SampleSet& samples,
                               const Eigen::Isometry3d& X_LU, const Problem& problem) {
  if (SpikePatchCap(*problem.request) <= 0.0) return std::vector<bool>(samples.size(), false);
  // The penetrating samples as the set's evaluation measures them, within the seat window.
  const double reach = std::max(SeatSettings(stage, *problem.request).window_mm, 0.5);
  const std::vector<char> flags =
      SpikeFlags(MeasureSet(stage, samples, X_LU, reach, reach), samples, *problem.request);
  return std::vector<bool>(flags.begin(), flags.end());
}

namespace {

// What pass 2 of EvaluateSet gathers besides the SetEvaluation itself.
struct SetTotals {
  std::vector<std::pair<double, double>> pen_kept;  // (depth, area) of non-spike penetration
  double deep_area = 0.0, left = 0.0, right = 0.0, near_area = 0.0;
};

// Weight of a sample at gap d in the smooth contact score: 1 within the band, falling
// smoothly to 0 at the attraction range.
double SmoothWeight(double d, double band, double range) {
  if (d <= band) return 1.0;
  const double s = (d - band) / (range - band);
  return (1.0 - s * s) * (1.0 - s * s);
}

// What a caller of EvaluateSet needs: everything, or only the penetration measure and the
// smallest known distance (the settle), which skips the seat cost, contact and smooth score.
enum class SetParts { kAll, kPenetration };

// Pass 2: seat cost, contact, penetration and the smooth score; spike samples are left out of
// the penalty and the measure.
void AccumulateSet(const SampleSet& samples, const Eigen::Isometry3d& X_LU, const Problem& problem,
                   const ResidualSettings& seat, const SetDistances& m,
                   const std::vector<char>& spike, SetParts parts, SetEvaluation* e, SetTotals* t) {
  const bool score = parts == SetParts::kAll;
  const PlanRequest& req = *problem.request;
  const double band = req.contact_band_mm, range = req.attraction_range_mm;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double d = m.dist[i];
    const double a = samples.area_mm2[i];
    const bool attract = samples.facing[i] >= seat.attraction_min_facing;
    if (spike[i]) {
      e->max_penetration_mm = std::max(e->max_penetration_mm, -d);
      if (score) e->seat_cost += SeatSampleCost(0.0, a, attract, seat);
      continue;
    }
    if (score) e->seat_cost += SeatSampleCost(d, a, attract, seat);
    if (!m.known[i]) {
      if (m.deep[i]) {
        ++e->deep;
        t->deep_area += a;
      }
      continue;
    }
    e->min_distance_mm = std::min(e->min_distance_mm, d);
    if (d > range) continue;
    if (d <= band) t->near_area += a;
    if (d < 0.0) {
      t->pen_kept.emplace_back(-d, a);
      e->max_penetration_mm = std::max(e->max_penetration_mm, -d);
      const double excess = -d - req.max_penetration_mm;
      if (excess > 0.0) e->excess_rms_mm += a * excess * excess;
    }
    if (!score) continue;
    if (d >= 0.0 && d <= band) e->contact_area_mm2 += a;
    const double k = SmoothWeight(d, band, range);
    e->smooth_score += a * k;
    const Eigen::Vector3d rel = X_LU * samples.p_U[i] - problem.arch.origin_L;
    if (req.bilateral_posterior_weight > 0.0 &&
        rel.dot(problem.arch.anterior_L) <= problem.arch.anterior_split_mm) {
      (rel.dot(problem.arch.lateral_L) >= 0.0 ? t->left : t->right) += a * k;
    }
  }
}

// The bilateral penalty, the excess RMS and the outlier-robust penetration from the totals.
void FinishSet(const OracleStage& stage, const SampleSet& samples, const PlanRequest& req,
               const SetTotals& t, SetEvaluation* e) {
  e->smooth_score -= req.bilateral_posterior_weight * std::abs(t.left - t.right);
  e->excess_rms_mm = std::sqrt(e->excess_rms_mm / std::max(t.near_area, 1.0));
  const double deep_depth = stage.oracle->lower_sdf().band_mm();
  const double mean_area = e->deep > 0 ? t.deep_area / static_cast<double>(e->deep) : 0.0;
  // A cluster stands for spacing^2 of surface; a budget below one cluster would make the
  // coarse stages ignore the request's outlier handling, so allow at least one.
  double budget = OutlierBudget(req, t.near_area);
  if (budget > 0.0) budget = std::max(budget, 1.01 * samples.spacing_mm * samples.spacing_mm);
  e->robust_penetration_mm = RobustPenetration(t.pen_kept, e->deep, deep_depth, mean_area, budget);
  if (e->deep > 0) e->max_penetration_mm = std::max(e->max_penetration_mm, deep_depth);
  e->feasible = e->robust_penetration_mm <= req.max_penetration_mm;
}

SetEvaluation EvaluateSetParts(const OracleStage& stage, const SampleSet& samples,
                               const Eigen::Isometry3d& X_LU, const Problem& problem,
                               SetParts parts) {
  const PlanRequest& req = *problem.request;
  const ResidualSettings seat = SeatSettings(stage, req);
  const double reach = std::max({req.attraction_range_mm, seat.window_mm, 0.5});
  const SetDistances m = MeasureSet(stage, samples, X_LU, reach, seat.window_mm);
  const std::vector<char> spike = SpikeFlags(m, samples, req);
  SetEvaluation e;
  e.min_distance_mm = std::numeric_limits<double>::infinity();
  SetTotals totals;
  AccumulateSet(samples, X_LU, problem, seat, m, spike, parts, &e, &totals);
  FinishSet(stage, samples, req, totals, &e);
  return e;
}

}  // namespace

SetEvaluation EvaluateSet(const OracleStage& stage, const SampleSet& samples,
                          const Eigen::Isometry3d& X_LU, const Problem& problem) {
  return EvaluateSetParts(stage, samples, X_LU, problem, SetParts::kAll);
}

namespace {

// Range [lo, hi] of h such that Clamp leaves x + h * (settle_dir, 0) unchanged.
void SettleRange(const Problem& problem, const Vector6d& x, double* lo, double* hi) {
  *lo = -20.0;
  *hi = 20.0;
  for (int i = 0; i < 3; ++i) {
    const double u = problem.settle_dir[i];
    if (std::abs(u) < 1e-12) continue;
    const double a = (problem.lower[i] - x[i]) / u, b = (problem.upper[i] - x[i]) / u;
    *lo = std::max(*lo, std::min(a, b));
    *hi = std::min(*hi, std::max(a, b));
  }
  *lo = std::min(*lo, 0.0);
  *hi = std::max(*hi, 0.0);
}

// Generic settle: `measure(h)` returns (penetration measure, smallest known distance).
template <typename Measure>
double SettleOffset(const Problem& problem, const Vector6d& x, Measure measure,
                    double first_step_mm, double tolerance_mm) {
  const double limit = problem.request->max_penetration_mm;
  double lo = 0.0, hi = 0.0;
  SettleRange(problem, x, &lo, &hi);
  if (problem.settle_dir.squaredNorm() == 0.0) return 0.0;
  double closed = 0.0, open = 0.0;  // infeasible / feasible offsets
  auto [pen0, dist0] = measure(0.0);
  if (pen0 <= limit) {
    // Close: jump by the known gap, else double the step, until infeasible.
    double h = 0.0, step = first_step_mm, dist = dist0;
    for (;;) {
      const double jump = std::isfinite(dist) && dist > 0.1 ? dist - 0.05 : step;
      const double next = std::max(lo, h - jump);
      if (next >= h) return h;  // at the bound, still feasible
      auto [pen, d] = measure(next);
      if (pen > limit) {
        closed = next;
        open = h;
        break;
      }
      h = next;
      dist = d;
      step *= 2.0;
    }
  } else {
    double h = 0.0, step = first_step_mm;
    for (;;) {
      const double next = std::min(hi, h + step);
      if (next <= h) return h;  // at the bound, still infeasible: least penetrating reachable
      auto [pen, d] = measure(next);
      (void)d;
      if (pen <= limit) {
        closed = h;
        open = next;
        break;
      }
      h = next;
      step *= 2.0;
    }
  }
  while (open - closed > tolerance_mm) {
    const double mid = 0.5 * (open + closed);
    (measure(mid).first > limit ? closed : open) = mid;
  }
  return open;
}

Vector6d Offset(const Problem& problem, const Vector6d& x, double h) {
  Vector6d y = x;
  y.head<3>() += h * problem.settle_dir;
  return y;
}

}  // namespace

Vector6d SettleOnSet(const OracleStage& stage, const SampleSet& samples, const Problem& problem,
                     const Vector6d& x, int* evaluations) {
  const double h = SettleOffset(
      problem, x,
      [&](double offset) {
        ++*evaluations;
        const SetEvaluation e =
            EvaluateSetParts(stage, samples, PoseOf(problem, Offset(problem, x, offset)), problem,
                             SetParts::kPenetration);
        return std::make_pair(e.robust_penetration_mm, e.min_distance_mm);
      },
      0.25, 0.003);
  return Offset(problem, x, h);
}

Vector6d SettleOnOracle(const OracleStage& stage, const Problem& problem, const Vector6d& x,
                        int* evaluations) {
  const double h = SettleOffset(
      problem, x,
      [&](double offset) {
        ++*evaluations;
        const PoseEvaluation e =
            EvaluatePose(stage, PoseOf(problem, Offset(problem, x, offset)), *problem.request);
        // Only step by known gaps within the oracle's reach.
        return std::make_pair(e.constrained_penetration_mm,
                              std::numeric_limits<double>::quiet_NaN());
      },
      0.02, 0.003);
  return Offset(problem, x, h);
}

}  // namespace occlude::planner::detail
