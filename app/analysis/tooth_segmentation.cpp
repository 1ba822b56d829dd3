// Segmentation of the crown profile into teeth (tooth_segmentation.h). The programme works on
// stations kStationMm apart: a tooth is two boundaries; each boundary costs kValleyWeight times
// its valley depth (profile / local maximum, 0 at a gap, 1 on a crown), each tooth the squared
// relative deviation of its width from scale x typical width over kWidthSigma, and crown left
// beyond a side's last tooth kLeftOverWeight per mm of typical crown.
#include "tooth_segmentation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry_util.h"

namespace occlude::analysis {
namespace {

constexpr double kStationMm = 0.5;
constexpr double kValleyWindowMm = 3.0;  // a valley is low against the profile this far around
constexpr double kValleyWeight = 3.0;
constexpr double kWidthSigma = 0.15;
constexpr double kMaxWidthZ = 2.5;  // an odd width costs at most this squared
constexpr double kLeftOverWeight = 0.2;
// Third molars are often missing or unerupted, and the gingiva rising behind the second molars
// to the ramus looks like one: the eighth tooth of a side costs this much more.
constexpr double kThirdMolarCost = 4.0;
constexpr double kMinMass = 0.5;     // a tooth holds at least half the typical crown per mm ...
constexpr double kThinWeight = 8.0;  // ... else costs up to this much
constexpr double kMidlineSearchMm = 6.0;  // the midline lies this close to the mirror axis ...
constexpr double kMidlineSigmaMm = 2.0;   // ... each sigma away costing squared
constexpr double kMinScale = 0.85, kMaxScale = 1.2, kScaleStep = 0.025;
constexpr int kMinTeethPerSide = 3, kMaxTeethPerSide = 8;
constexpr double kEndShare = 0.25;
constexpr double kLastToothMaxShare = 1.0;  // a crown ends where its weight falls below this share
// Crowns are told apart by valleys: when the median tooth's boundaries are shallower than this
// (confidence = 1 - mean valley depth), the surface has no crowns (a box, a dome, a flat base).
// The c-cases' medians are 0.46-0.75.
constexpr double kMinMedianConfidence = 0.2;
constexpr double kRefineMm = 0.75;  // boundaries then move to the profile's minimum this close
constexpr double kInf = std::numeric_limits<double>::infinity();

// Typical widths along the arch (Wheeler's dental anatomy, rounded), positions 1-8.
constexpr double kUpperWidthMm[8] = {8.5, 6.5, 7.5, 7.0, 6.5, 10.0, 9.0, 8.5};
constexpr double kLowerWidthMm[8] = {5.0, 5.5, 7.0, 7.0, 7.0, 11.0, 10.5, 10.0};

struct Problem {
  std::vector<double> valley;  // per station, in [0, 1]
  std::vector<double> mass;    // prefix sums of profile / typical profile, per station
  std::vector<double> left_over_right, left_over_left;  // crown beyond station k, per side
  io::Jaw jaw = io::Jaw::kLower;
  int n = 0;
};

struct SidePlan {
  double cost = kInf;
  std::vector<int> bounds;  // outward from the midline, excluding it
};

// Averages of `v` over consecutive groups of `per` entries.
std::vector<double> Downsample(const std::vector<double>& v, int per) {
  std::vector<double> out;
  for (std::size_t k = 0; k < v.size(); k += static_cast<std::size_t>(per)) {
    const std::size_t end = std::min(v.size(), k + static_cast<std::size_t>(per));
    double sum = 0.0;
    for (std::size_t i = k; i < end; ++i) sum += v[i];
    out.push_back(sum / static_cast<double>(end - k));
  }
  return out;
}

// Per entry, v over the largest v within +-r entries (0 where that is 0).
std::vector<double> ValleyDepth(const std::vector<double>& v, int r) {
  const int n = static_cast<int>(v.size());
  std::vector<double> out(v.size(), 0.0);
  for (int k = 0; k < n; ++k) {
    double top = 0.0;
    for (int i = std::max(0, k - r); i <= std::min(n - 1, k + r); ++i) {
      top = std::max(top, v[static_cast<std::size_t>(i)]);
    }
    out[static_cast<std::size_t>(k)] = top > 0.0 ? v[static_cast<std::size_t>(k)] / top : 0.0;
  }
  return out;
}

Problem MakeProblem(const CrownProfile& profile, double step, io::Jaw jaw) {
  Problem pb;
  pb.jaw = jaw;
  const int per = std::max(1, static_cast<int>(std::lround(kStationMm / step)));
  const std::vector<double> p = Downsample(profile.material, per);
  pb.n = static_cast<int>(p.size());
  const int r = static_cast<int>(std::lround(kValleyWindowMm / kStationMm));
  const std::vector<double> by_material = ValleyDepth(p, r);
  const std::vector<double> by_weight = ValleyDepth(Downsample(profile.weight, per), r);
  pb.valley.resize(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) pb.valley[k] = 0.5 * (by_material[k] + by_weight[k]);
  std::vector<double> crowned;
  for (const double v : p) {
    if (v > 0.0) crowned.push_back(v);
  }
  const double typical = std::max(Quantile(crowned, 0.5), 1e-9);
  pb.mass.assign(p.size() + 1, 0.0);
  for (std::size_t k = 0; k < p.size(); ++k) pb.mass[k + 1] = pb.mass[k] + p[k] / typical;
  pb.left_over_right.assign(p.size(), 0.0);
  pb.left_over_left.assign(p.size(), 0.0);
  for (int k = 1; k < pb.n; ++k) {
    pb.left_over_right[static_cast<std::size_t>(k)] =
        pb.left_over_right[static_cast<std::size_t>(k - 1)] +
        p[static_cast<std::size_t>(k - 1)] / typical * kStationMm;
  }
  for (int k = pb.n - 2; k >= 0; --k) {
    pb.left_over_left[static_cast<std::size_t>(k)] =
        pb.left_over_left[static_cast<std::size_t>(k + 1)] +
        p[static_cast<std::size_t>(k + 1)] / typical * kStationMm;
  }
  return pb;
}

// The best teeth of one side from midline station m outward (dir -1: towards station 0, the
// patient's right; +1: the left).
SidePlan PlanSide(const Problem& pb, int m, int dir, double scale) {
  std::vector<std::vector<double>> f(kMaxTeethPerSide + 1,
                                     std::vector<double>(static_cast<std::size_t>(pb.n), kInf));
  std::vector<std::vector<int>> from(kMaxTeethPerSide + 1,
                                     std::vector<int>(static_cast<std::size_t>(pb.n), -1));
  f[0][static_cast<std::size_t>(m)] = 0.0;
  SidePlan best;
  int best_p = 0, best_k = -1;
  for (int p = 1; p <= kMaxTeethPerSide; ++p) {
    const double want = scale * TypicalWidthMm(pb.jaw, p);
    const int lo = static_cast<int>(std::ceil(0.6 * want / kStationMm));
    const int hi = static_cast<int>(std::floor(1.5 * want / kStationMm));
    for (int kp = 0; kp < pb.n; ++kp) {
      const double prev = f[static_cast<std::size_t>(p - 1)][static_cast<std::size_t>(kp)];
      if (prev == kInf) continue;
      for (int d = lo; d <= hi; ++d) {
        const int k = kp + dir * d;
        if (k < 0 || k >= pb.n) break;
        const double z =
            std::min(kMaxWidthZ, std::abs(d * kStationMm - want) / (kWidthSigma * want));
        const double mass = std::abs(pb.mass[static_cast<std::size_t>(std::max(k, kp))] -
                                     pb.mass[static_cast<std::size_t>(std::min(k, kp))]) /
                            d;
        const double c = prev + z * z + kValleyWeight * pb.valley[static_cast<std::size_t>(k)] +
                         kThinWeight * std::max(0.0, kMinMass - mass) / kMinMass +
                         (p == 8 ? kThirdMolarCost : 0.0);
        if (c < f[static_cast<std::size_t>(p)][static_cast<std::size_t>(k)]) {
          f[static_cast<std::size_t>(p)][static_cast<std::size_t>(k)] = c;
          from[static_cast<std::size_t>(p)][static_cast<std::size_t>(k)] = kp;
        }
      }
    }
    if (p < kMinTeethPerSide) continue;
    for (int k = 0; k < pb.n; ++k) {
      const double fk = f[static_cast<std::size_t>(p)][static_cast<std::size_t>(k)];
      if (fk == kInf) continue;
      const double rest =
          kLeftOverWeight *
          (dir < 0 ? pb.left_over_right : pb.left_over_left)[static_cast<std::size_t>(k)];
      if (fk + rest < best.cost) best.cost = fk + rest, best_p = p, best_k = k;
    }
  }
  for (int p = best_p, k = best_k; p > 0;
       k = from[static_cast<std::size_t>(p)][static_cast<std::size_t>(k)], --p) {
    best.bounds.insert(best.bounds.begin(), k);
  }
  return best;
}

// Moves a boundary to the lowest profile value within kRefineMm (full resolution).
double RefineBoundary(const std::vector<double>& profile, double step, double s) {
  const long k0 = std::lround(s / step), r = std::lround(kRefineMm / step);
  long best = std::clamp(k0, 0L, static_cast<long>(profile.size()) - 1);
  for (long k = std::max(0L, k0 - r); k <= std::min(static_cast<long>(profile.size()) - 1, k0 + r);
       ++k) {
    if (profile[static_cast<std::size_t>(k)] < profile[static_cast<std::size_t>(best)]) best = k;
  }
  return step * static_cast<double>(best);
}

// The outer boundary of a side's last tooth is where its crown ends, not where the programme
// put it (often the end of the scan): moves `*outer` towards `inner` while the crown weight
// stays below kEndShare of the tooth's median.
void TrimEnd(const CrownProfile& profile, double step, double* outer, double inner) {
  const auto index = [&](double s) {
    return std::clamp(std::lround(s / step), 0L, static_cast<long>(profile.weight.size()) - 1);
  };
  const long a = index(*outer), b = index(inner), dir = b > a ? 1 : -1;
  std::vector<double> w;
  for (long k = a; k != b; k += dir) w.push_back(profile.weight[static_cast<std::size_t>(k)]);
  const double limit = kEndShare * Quantile(w, 0.5);
  long k = a;
  while (k != b && profile.weight[static_cast<std::size_t>(k)] < limit) k += dir;
  *outer = step * static_cast<double>(k);
}

// The outer ends of the two sides' last teeth: where their crowns end (TrimEnd), and no longer
// than the arch's scaled typical width times kLastToothMaxShare (the gingiva rising behind the
// last molar towards the ramus looks like crown).
void FinishEnds(const CrownProfile& profile, double step, io::Jaw jaw, double scale,
                std::vector<ToothSpan>* teeth) {
  ToothSpan& right = teeth->front();
  ToothSpan& left = teeth->back();
  TrimEnd(profile, step, &right.s_lo, right.s_hi);
  TrimEnd(profile, step, &left.s_hi, left.s_lo);
  const auto longest = [&](const ToothSpan& t) {
    return kLastToothMaxShare * scale * TypicalWidthMm(jaw, io::ToothPosition(t.fdi));
  };
  right.s_lo = std::max(right.s_lo, right.s_hi - longest(right));
  left.s_hi = std::min(left.s_hi, left.s_lo + longest(left));
}

}  // namespace

double TypicalWidthMm(io::Jaw jaw, int position) {
  const int i = std::clamp(position, 1, 8) - 1;
  return jaw == io::Jaw::kUpper ? kUpperWidthMm[i] : kLowerWidthMm[i];
}

CrownProfile MakeCrownProfile(const HeightMap& map, const std::vector<double>& crown,
                              const std::vector<ArchCurve::Projection>& cell_st,
                              const ArchCurve& curve, double floor, double half_width_mm) {
  CrownProfile profile;
  profile.material.assign(curve.q.size(), 0.0);
  profile.weight.assign(curve.q.size(), 0.0);
  const double area = map.cell * map.cell / curve.step;
  for (std::size_t c = 0; c < crown.size(); ++c) {
    if (crown[c] <= 0.0 || std::abs(cell_st[c].t) > half_width_mm) continue;
    const long k = std::lround(cell_st[c].s / curve.step);
    if (k < 0 || k >= static_cast<long>(curve.q.size())) continue;
    profile.material[static_cast<std::size_t>(k)] += (map.height[c] - floor) * area;
    profile.weight[static_cast<std::size_t>(k)] += crown[c] * area;
  }
  return profile;
}

std::vector<ToothSpan> SegmentTeeth(const CrownProfile& profile, const ArchCurve& curve,
                                    io::Jaw jaw, std::string* why) {
  const Problem pb = MakeProblem(profile, curve.step, jaw);
  const int apex = static_cast<int>(std::lround(curve.symmetry_s / kStationMm));
  const int reach = static_cast<int>(std::lround(kMidlineSearchMm / kStationMm));
  double best = kInf, best_scale = 1.0;
  int best_m = -1;
  SidePlan best_right, best_left;
  for (double scale = kMinScale; scale <= kMaxScale + 1e-9; scale += kScaleStep) {
    for (int m = std::max(0, apex - reach); m <= std::min(pb.n - 1, apex + reach); ++m) {
      const SidePlan right = PlanSide(pb, m, -1, scale);
      const SidePlan left = PlanSide(pb, m, +1, scale);
      const double cost =
          right.cost + left.cost + kValleyWeight * pb.valley[static_cast<std::size_t>(m)];
      if (cost < best) {
        best = cost, best_scale = scale, best_m = m, best_right = right, best_left = left;
      }
    }
  }
  if (best_m < 0 || best == kInf) {
    *why = "no arrangement of teeth fits the crowns along the arch";
    return {};
  }
  std::vector<ToothSpan> teeth;
  const auto add = [&](int position, int inner, int outer, bool right) {
    ToothSpan t;
    const int quadrant = jaw == io::Jaw::kUpper ? (right ? 1 : 2) : (right ? 4 : 3);
    t.fdi = 10 * quadrant + position;
    const double a = RefineBoundary(profile.weight, curve.step, inner * kStationMm);
    const double b = RefineBoundary(profile.weight, curve.step, outer * kStationMm);
    t.s_lo = std::min(a, b);
    t.s_hi = std::max(a, b);
    const double v = 0.5 * (pb.valley[static_cast<std::size_t>(inner)] +
                            pb.valley[static_cast<std::size_t>(outer)]);
    t.confidence = std::clamp(1.0 - v, 0.0, 1.0);
    teeth.push_back(t);
  };
  for (int p = static_cast<int>(best_right.bounds.size()); p >= 1; --p) {
    add(p, p == 1 ? best_m : best_right.bounds[static_cast<std::size_t>(p - 2)],
        best_right.bounds[static_cast<std::size_t>(p - 1)], true);
  }
  for (int p = 1; p <= static_cast<int>(best_left.bounds.size()); ++p) {
    add(p, p == 1 ? best_m : best_left.bounds[static_cast<std::size_t>(p - 2)],
        best_left.bounds[static_cast<std::size_t>(p - 1)], false);
  }
  std::vector<double> confidence;
  for (const ToothSpan& t : teeth) confidence.push_back(t.confidence);
  if (teeth.empty() || Quantile(confidence, 0.5) < kMinMedianConfidence) {
    *why = "no crowns along the arch (no valleys between crowns: median boundary contrast " +
           std::to_string(confidence.empty() ? 0.0 : Quantile(confidence, 0.5)) + ")";
    return {};
  }
  FinishEnds(profile, curve.step, jaw, best_scale, &teeth);
  return teeth;
}

}  // namespace occlude::analysis
