// Fitting and evaluating the arch curve (arch_curve.h): one-degree bins of polar angle, the
// band's middle radius per bin (between its 10th and 90th percentile radii), a median and a
// mean filter over bins, resampling by arc length.
#include "arch_curve.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry_util.h"
#include "occlude/angles.h"

namespace occlude::analysis {
namespace {

constexpr int kBins = 360;
constexpr int kMinCellsPerBin = 4;
constexpr int kMaxGapBins = 6;  // gaps of up to this many empty bins are bridged

constexpr int kDegree = 8;        // of the radius polynomial: smooth below a tooth's width
constexpr double kHuberMm = 1.0;  // radius residuals beyond this count less
constexpr double kSymmetrySearchMm = 10.0;
constexpr double kSymmetryFromMm = 3.0, kSymmetryToMm = 15.0;
constexpr double kEndWeightShare = 0.2;  // end bins lighter than this share of the median: gingiva

struct Bin {
  std::vector<double> r, h, w;
  double weight = 0.0;
};

// The radius that splits the bin's weight in half.
double WeightedMedianRadius(const Bin& bin) {
  std::vector<std::size_t> order(bin.r.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return bin.r[a] < bin.r[b]; });
  double acc = 0.0;
  for (const std::size_t i : order) {
    acc += bin.w[i];
    if (acc >= 0.5 * bin.weight) return bin.r[i];
  }
  return bin.r[order.back()];
}

double BinAngle(int b) { return -kPi + (b + 0.5) * 2.0 * kPi / kBins; }

// The longest run of usable bins, allowing short gaps; [first, last] inclusive.
std::pair<int, int> LongestRun(const std::vector<bool>& ok) {
  int best_first = -1, best_last = -2, first = -1, last = -2;
  for (int b = 0; b < kBins; ++b) {
    if (!ok[static_cast<std::size_t>(b)]) continue;
    if (first >= 0 && b - last - 1 <= kMaxGapBins) {
      last = b;
    } else {
      first = last = b;
    }
    if (last - first > best_last - best_first) best_first = first, best_last = last;
  }
  return {best_first, best_last};
}

// Fills empty entries of v over [first, last] by linear interpolation between valid ones.
void Bridge(std::vector<double>* v, const std::vector<bool>& ok, int first, int last) {
  int prev = first;
  for (int b = first + 1; b <= last; ++b) {
    if (!ok[static_cast<std::size_t>(b)]) continue;
    for (int g = prev + 1; g < b; ++g) {
      const double f = static_cast<double>(g - prev) / (b - prev);
      (*v)[static_cast<std::size_t>(g)] =
          (1 - f) * (*v)[static_cast<std::size_t>(prev)] + f * (*v)[static_cast<std::size_t>(b)];
    }
    prev = b;
  }
}

std::vector<double> Smooth(const std::vector<double>& v, int first, int last, int half,
                           bool median) {
  std::vector<double> out = v;
  for (int b = first; b <= last; ++b) {
    std::vector<double> w;
    for (int k = std::max(first, b - half); k <= std::min(last, b + half); ++k) {
      w.push_back(v[static_cast<std::size_t>(k)]);
    }
    double mean = 0.0;
    for (double x : w) mean += x;
    out[static_cast<std::size_t>(b)] =
        median ? Quantile(w, 0.5) : mean / static_cast<double>(w.size());
  }
  return out;
}

// Stations every `step` mm along the polyline through `points` (with heights `tops`).
void Resample(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& tops,
              double step, ArchCurve* curve) {
  double s = 0.0, next = 0.0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const double len = (points[i + 1] - points[i]).norm();
    while (next <= s + len && len > 0.0) {
      const double f = (next - s) / len;
      curve->q.push_back((1 - f) * points[i] + f * points[i + 1]);
      curve->top.push_back((1 - f) * tops[i] + f * tops[i + 1]);
      next += step;
    }
    s += len;
  }
}

}  // namespace

double ArchAngle(const Eigen::Vector2d& c, const Eigen::Vector2d& p) {
  return std::atan2(-(p.x() - c.x()), p.y() - c.y());
}

Eigen::Vector2d ArchCurve::At(double s) const {
  const double f = std::clamp(s / step, 0.0, static_cast<double>(q.size() - 1));
  const auto k = std::min(static_cast<std::size_t>(f), q.size() - 2);
  const double a = f - static_cast<double>(k);
  const Eigen::Vector2d p = (1 - a) * q[k] + a * q[k + 1];
  if (s < 0.0) return q.front() + s * Tangent(0.0);
  if (s > Length()) return q.back() + (s - Length()) * Tangent(Length());
  return p;
}

Eigen::Vector2d ArchCurve::Tangent(double s) const {
  const double f = std::clamp(s / step, 0.0, static_cast<double>(q.size() - 1));
  const auto k = std::min(static_cast<std::size_t>(f), q.size() - 2);
  const std::size_t lo = k >= 2 ? k - 2 : 0, hi = std::min(q.size() - 1, k + 3);
  return (q[hi] - q[lo]).normalized();
}

Eigen::Vector2d ArchCurve::Normal(double s) const {
  const Eigen::Vector2d t = Tangent(s);
  return {-t.y(), t.x()};
}

double ArchCurve::TopAt(double s) const {
  const double f = std::clamp(s / step, 0.0, static_cast<double>(q.size() - 1));
  const auto k = std::min(static_cast<std::size_t>(f), q.size() - 2);
  const double a = f - static_cast<double>(k);
  return (1 - a) * top[k] + a * top[k + 1];
}

ArchCurve::Projection ArchCurve::Project(const Eigen::Vector2d& p) const {
  // Stations are ordered by decreasing angle; start the search at the matching angle.
  const double a = ArchAngle(centre, p);
  const auto it = std::lower_bound(angle.begin(), angle.end(), a, std::greater<double>());
  const auto k0 = static_cast<long>(it - angle.begin());
  const long n = static_cast<long>(q.size());
  const long window = static_cast<long>(std::ceil(12.0 / step));
  const long first = std::max(0L, k0 - window), end = std::min(n - 1, k0 + window);
  if (first >= end) return {};
  // The nearest segment of the window (the lowest k among equals), searched outward from the
  // angle's: an inner segment (a chord of at most `step`) whose middle lies farther than the
  // best distance plus half a step (and a margin far beyond rounding) cannot be nearer, and is
  // passed over without its foot. The two end segments extend past the ends: never passed over.
  double best = std::numeric_limits<double>::infinity(), reach = best;
  long best_k = -1;
  double best_f = 0.0;
  const auto visit = [&](long k) {
    const Eigen::Vector2d& qk = q[static_cast<std::size_t>(k)];
    const Eigen::Vector2d& qn = q[static_cast<std::size_t>(k + 1)];
    if (k > 0 && k < n - 2 && (p - 0.5 * (qk + qn)).squaredNorm() > reach) return;
    const Eigen::Vector2d d = qn - qk;
    double f = (p - qk).dot(d) / d.squaredNorm();
    if (k > 0) f = std::max(f, 0.0);
    if (k < n - 2) f = std::min(f, 1.0);
    const double dist = (p - (qk + f * d)).squaredNorm();
    if (dist < best || (dist == best && k < best_k)) {
      best = dist;
      best_k = k;
      best_f = f;
      const double r = std::sqrt(best) + 0.5 * step + 1e-6;
      reach = r * r;
    }
  };
  const long start = std::clamp(k0, first, end - 1);
  for (long k = start; k < end; ++k) visit(k);
  for (long k = start - 1; k >= first; --k) visit(k);
  const Eigen::Vector2d d =
      q[static_cast<std::size_t>(best_k + 1)] - q[static_cast<std::size_t>(best_k)];
  const Eigen::Vector2d foot = q[static_cast<std::size_t>(best_k)] + best_f * d;
  Projection out;
  out.s = (static_cast<double>(best_k) + best_f) * step;
  const Eigen::Vector2d normal(-d.y(), d.x());
  out.t = (p - foot).dot(normal.normalized());
  return out;
}

namespace {

// Weighted least-squares polynomial r(a) of degree kDegree through the bins' radii over
// [first, last] (in Legendre polynomials of the normalised angle), with two rounds of Huber
// reweighting so that a few gingiva bins do not bend it.
std::vector<double> SmoothRadius(const std::vector<double>& radius,
                                 const std::vector<double>& weight, int first, int last) {
  const int n = last - first + 1;
  const auto basis = [&](int b, int k) {
    const double x = 2.0 * (b - first) / std::max(1, last - first) - 1.0;
    double p0 = 1.0, p1 = x;
    if (k == 0) return p0;
    for (int m = 1; m < k; ++m) {
      const double p2 = ((2 * m + 1) * x * p1 - m * p0) / (m + 1);
      p0 = p1;
      p1 = p2;
    }
    return p1;
  };
  std::vector<double> w(weight.begin() + first, weight.begin() + last + 1);
  Eigen::VectorXd coef = Eigen::VectorXd::Zero(kDegree + 1);
  for (int round = 0; round < 3; ++round) {
    Eigen::MatrixXd A(n, kDegree + 1);
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; ++i) {
      const double sw = std::sqrt(std::max(w[static_cast<std::size_t>(i)], 0.0));
      for (int k = 0; k <= kDegree; ++k) A(i, k) = sw * basis(first + i, k);
      y(i) = sw * radius[static_cast<std::size_t>(first + i)];
    }
    coef = A.colPivHouseholderQr().solve(y);
    for (int i = 0; i < n; ++i) {
      double fit = 0.0;
      for (int k = 0; k <= kDegree; ++k) fit += coef(k) * basis(first + i, k);
      const double r = std::abs(fit - radius[static_cast<std::size_t>(first + i)]);
      w[static_cast<std::size_t>(i)] =
          weight[static_cast<std::size_t>(first + i)] * (r <= kHuberMm ? 1.0 : kHuberMm / r);
    }
  }
  std::vector<double> out = radius;
  for (int b = first; b <= last; ++b) {
    double fit = 0.0;
    for (int k = 0; k <= kDegree; ++k) fit += coef(k) * basis(b, k);
    out[static_cast<std::size_t>(b)] = fit;
  }
  return out;
}

// ArchCurve::symmetry_s: the station within kSymmetrySearchMm of the apex minimising the
// squared anterior differences of the stations kSymmetryFromMm-kSymmetryToMm on either side.
double SymmetryAxis(const ArchCurve& curve) {
  const double len = curve.Length();
  double best_s = curve.apex_s, best = std::numeric_limits<double>::infinity();
  for (double m = curve.apex_s - kSymmetrySearchMm; m <= curve.apex_s + kSymmetrySearchMm;
       m += curve.step) {
    if (m - kSymmetryToMm < 0.0 || m + kSymmetryToMm > len) continue;
    double cost = 0.0;
    for (double d = kSymmetryFromMm; d <= kSymmetryToMm; d += 1.0) {
      cost += std::pow(curve.At(m + d).y() - curve.At(m - d).y(), 2);
    }
    if (cost < best) best = cost, best_s = m;
  }
  return best_s;
}

}  // namespace

std::optional<ArchCurve> FitArchCurve(const HeightMap& map, const std::vector<double>& crown,
                                      const Eigen::Vector2d& centre, double step,
                                      std::string* why) {
  std::vector<Bin> bins(kBins);
  for (int c = 0; c < map.nx * map.ny; ++c) {
    const double w = crown[static_cast<std::size_t>(c)];
    if (w <= 0.0) continue;
    const Eigen::Vector2d p = map.Centre(c);
    const double a = ArchAngle(centre, p);
    const int b = std::clamp(static_cast<int>((a + kPi) / (2 * kPi) * kBins), 0, kBins - 1);
    Bin& bin = bins[static_cast<std::size_t>(b)];
    const double h = map.height[static_cast<std::size_t>(c)];
    bin.r.push_back((p - centre).norm());
    bin.h.push_back(h);
    bin.w.push_back(w);
    bin.weight += w;
  }
  std::vector<bool> ok(kBins);
  std::vector<double> radius(kBins, 0.0), top(kBins, 0.0), weight(kBins, 0.0);
  for (int b = 0; b < kBins; ++b) {
    const Bin& bin = bins[static_cast<std::size_t>(b)];
    ok[static_cast<std::size_t>(b)] = static_cast<int>(bin.r.size()) >= kMinCellsPerBin;
    if (!ok[static_cast<std::size_t>(b)]) continue;
    weight[static_cast<std::size_t>(b)] = bin.weight;
    radius[static_cast<std::size_t>(b)] = WeightedMedianRadius(bin);
    top[static_cast<std::size_t>(b)] = *std::max_element(bin.h.begin(), bin.h.end());
  }
  auto [first, last] = LongestRun(ok);
  if (first < 0) {  // no bin holds enough crown cells (a tiny or flat mesh)
    *why = "no arch of crowns found (too few crown cells about its centre)";
    return std::nullopt;
  }
  // The band's ends: trim bins much lighter than the run's median (gingiva behind the molars).
  std::vector<double> run_weights(weight.begin() + std::max(first, 0), weight.begin() + last + 1);
  const double light = kEndWeightShare * Quantile(run_weights, 0.5);
  while (first < last && weight[static_cast<std::size_t>(first)] < light) ++first;
  while (last > first && weight[static_cast<std::size_t>(last)] < light) --last;
  if (last - first < 60) {  // less than a sixth of a turn: no arch
    *why = "no arch of crowns found (the crown band covers " +
           std::to_string(std::max(0, last - first + 1)) + " degrees about its centre)";
    return std::nullopt;
  }
  Bridge(&radius, ok, first, last);
  Bridge(&top, ok, first, last);
  radius = SmoothRadius(radius, weight, first, last);
  top = Smooth(top, first, last, 2, false);
  std::vector<Eigen::Vector2d> points;
  std::vector<double> tops;
  for (int b = last; b >= first; --b) {  // right (large angles) to left
    const double a = BinAngle(b);
    points.push_back(centre + radius[static_cast<std::size_t>(b)] *
                                  Eigen::Vector2d(-std::sin(a), std::cos(a)));
    tops.push_back(top[static_cast<std::size_t>(b)]);
  }
  ArchCurve curve;
  curve.step = step;
  curve.centre = centre;
  Resample(points, tops, step, &curve);
  for (const auto& p : curve.q) curve.angle.push_back(ArchAngle(centre, p));
  std::size_t apex = 0;
  for (std::size_t k = 0; k < curve.q.size(); ++k) {
    if (curve.q[k].y() > curve.q[apex].y()) apex = k;
  }
  curve.apex_s = step * static_cast<double>(apex);
  curve.symmetry_s = SymmetryAxis(curve);
  return curve;
}

}  // namespace occlude::analysis
