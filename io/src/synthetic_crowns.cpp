// Crown height functions of the synthetic teeth: how far each crown rises above (lower jaw)
// or hangs below (upper jaw) its gingiva at a point (s, t) of the parameter domain, mm.
#include <algorithm>
#include <cmath>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

// Shoulder profiles: flat over the crown's core, falling to 0 at its outline. Mesiodistally the
// core is wide and the fall steep (cubic), so neighbours meet high up (proximal contacts);
// buccolingually the fall is rounder (quadratic), like the convex buccal and lingual faces.
constexpr double kMesiodistalCore = 0.65;
constexpr double kBuccolingualCore = 0.45;

double Shoulder(double x, double core, int power) {
  if (x <= core) return 1.0;
  const double r = (x - core) / (1.0 - core);
  return 1.0 - (power == 3 ? r * r * r : r * r);
}

/// Relief of an incisor: an incisal edge along the arch at v = edge_v, falling quadratically
/// towards the lingual and labial faces (never deeper than half the crown).
double IncisalRelief(const Tooth& tooth, double v) {
  const double d = v - tooth.edge_v;
  const double k = d < 0.0 ? tooth.edge_lingual : tooth.edge_buccal;
  return std::max(-k * d * d, -0.5 * tooth.crown_height);
}

/// Relief of a cusped crown: the highest cusp bump, clamped to [floor, cap] (flat worn cusp
/// tips and flat fossa floors), minus the cap so that the tips are at the crown height.
double CuspRelief(const Tooth& tooth, double s, double t) {
  double highest = 0.0;
  for (const Cusp& cusp : tooth.cusps) {
    const double ds = s - cusp.s;
    const double dt = t - cusp.t;
    const double bump =
        cusp.amplitude * std::exp(-(ds * ds + dt * dt) / (2.0 * cusp.sigma * cusp.sigma));
    highest = std::max(highest, bump);
  }
  return std::clamp(highest, tooth.relief_floor, tooth.relief_cap) - tooth.relief_cap;
}

double CrownHeight(const Tooth& tooth, double s, double t) {
  const double u = std::abs(s - tooth.s_center) / tooth.half_length;
  const double v = (t - tooth.t_center) / tooth.half_width;
  if (u >= 1.0 || std::abs(v) >= 1.0) return 0.0;
  const double profile =
      Shoulder(u, kMesiodistalCore, 3) * Shoulder(std::abs(v), kBuccolingualCore, 2);
  const bool incisor = tooth.tooth_class == kCentralIncisor || tooth.tooth_class == kLateralIncisor;
  const double relief = incisor ? IncisalRelief(tooth, v) : CuspRelief(tooth, s, t);
  return profile * (tooth.crown_height + relief);
}

}  // namespace

CrownSample SampleCrowns(const JawLayout& jaw, double s, double t) {
  CrownSample best;
  for (std::size_t k = 0; k < jaw.teeth.size(); ++k) {
    const Tooth& tooth = jaw.teeth[k];
    if (std::abs(s - tooth.s_center) >= tooth.half_length) continue;
    const double h = CrownHeight(tooth, s, t);
    if (h > best.height) {
      best.height = h;
      best.tooth = static_cast<int>(k);
    }
  }
  return best;
}

}  // namespace occlude::io::synthetic
