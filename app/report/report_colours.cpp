// Contact map colours (see report_colours.h).
#include "report/report_colours.h"

#include <algorithm>

#include "viewer/contact_colours.h"

namespace occlude::app::render {
Rgb DistanceColour(double d, const MapScale& scale) {
  return ContactColour(d, {scale.max_mm, scale.band_mm, scale.penetration_from_mm});
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
