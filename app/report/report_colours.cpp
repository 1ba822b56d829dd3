// Contact map colours (see report_colours.h).
#include "report/report_colours.h"

#include <algorithm>

namespace occlude::app::render {
namespace {

struct Stop {
  double t;  ///< fraction of max_mm
  Rgb c;
};
// Red at contact, orange at 0.2 of the scale (the 0.1 mm band on the default 0.5 mm
// scale), yellow, green, blue at the end. Hues stay in 0..225 degrees, far from magenta.
constexpr Stop kStops[] = {{0.0, {205, 0, 0}},
                           {0.2, {255, 120, 0}},
                           {0.4, {250, 215, 0}},
                           {0.6, {40, 180, 40}},
                           {1.0, {30, 90, 230}}};

}  // namespace

Rgb DistanceColour(double d, const MapScale& scale) {
  if (d < -scale.penetration_from_mm) return kPenetrationColour;
  if (d > scale.max_mm) return kFarColour;
  const double t = std::clamp(d / scale.max_mm, 0.0, 1.0);
  for (std::size_t i = 1; i < std::size(kStops); ++i) {
    if (t <= kStops[i].t) {
      const double f = (t - kStops[i - 1].t) / (kStops[i].t - kStops[i - 1].t);
      Rgb out;
      for (std::size_t k = 0; k < 3; ++k) {
        out[k] = static_cast<std::uint8_t>(
            std::lround((1 - f) * kStops[i - 1].c[k] + f * kStops[i].c[k]));
      }
      return out;
    }
  }
  return kStops[std::size(kStops) - 1].c;
}

void ToHsv(Rgb c, double* hue, double* saturation, double* value) {
  const double r = c[0] / 255.0, g = c[1] / 255.0, b = c[2] / 255.0;
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b});
  const double d = mx - mn;
  *value = mx;
  *saturation = mx > 0 ? d / mx : 0.0;
  double h = 0.0;
  if (d > 0) {
    if (mx == r) {
      h = 60.0 * std::fmod((g - b) / d, 6.0);
    } else if (mx == g) {
      h = 60.0 * ((b - r) / d + 2.0);
    } else {
      h = 60.0 * ((r - g) / d + 4.0);
    }
  }
  *hue = h < 0 ? h + 360.0 : h;
}

bool IsContactColour(Rgb c) {
  double h, s, v;
  ToHsv(c, &h, &s, &v);
  return s > 0.6 && v > 0.2 && (h <= 32.0 || h >= 350.0);
}

bool IsPenetrationColour(Rgb c) {
  double h, s, v;
  ToHsv(c, &h, &s, &v);
  return s > 0.6 && v > 0.2 && h >= 285.0 && h <= 315.0;
}

}  // namespace occlude::app::render
