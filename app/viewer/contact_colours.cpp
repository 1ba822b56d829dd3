// The contact colour ramp (see contact_colours.h).
#include "viewer/contact_colours.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace occlude::app {
namespace {

struct Stop {
  double t;  ///< fraction of max_mm
  Rgb8 c;
};
// Red at contact, orange at 0.2 of the scale (the 0.1 mm band on the default 0.5 mm
// scale), yellow, green, blue at the end. Hues stay in 0..225 degrees, far from magenta.
constexpr Stop kStops[] = {{0.0, {205, 0, 0}},
                           {0.2, {255, 120, 0}},
                           {0.4, {250, 215, 0}},
                           {0.6, {40, 180, 40}},
                           {1.0, {30, 90, 230}}};

}  // namespace

Rgb8 ContactColour(double d, const ContactScale& scale) {
  if (d < -scale.penetration_from_mm) return kContactPenetrationColour;
  if (d > scale.max_mm) return kContactFarColour;
  const double t = std::clamp(d / scale.max_mm, 0.0, 1.0);
  for (std::size_t i = 1; i < std::size(kStops); ++i) {
    if (t <= kStops[i].t) {
      const double f = (t - kStops[i - 1].t) / (kStops[i].t - kStops[i - 1].t);
      Rgb8 out;
      for (std::size_t k = 0; k < 3; ++k) {
        out[k] = static_cast<std::uint8_t>(
            std::lround((1 - f) * kStops[i - 1].c[k] + f * kStops[i].c[k]));
      }
      return out;
    }
  }
  return kStops[std::size(kStops) - 1].c;
}

std::vector<std::pair<double, Rgb8>> ContactRampStops() {
  std::vector<std::pair<double, Rgb8>> out;
  for (const Stop& s : kStops) out.emplace_back(s.t, s.c);
  return out;
}

}  // namespace occlude::app
