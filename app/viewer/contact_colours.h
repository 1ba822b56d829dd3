// The contact map's colour ramp, callable without the report's raster code or
// OpenCV: signed distance to the opposing arch on a fixed mm scale, red (tight
// contact) through orange, yellow and green to blue (open, at max_mm); farther
// surface in a neutral ivory; penetration deeper than `penetration_from_mm` in
// magenta, a colour the ramp never uses. The one definition of the ramp: the report's
// still images (report/report_colours.h, DistanceColour) call it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace occlude::app {

using Rgb8 = std::array<std::uint8_t, 3>;

struct ContactScale {
  double max_mm = 0.5;                ///< colour ramp 0..max_mm
  double band_mm = 0.1;               ///< contact band (0 <= d <= band), marked on the legend
  double penetration_from_mm = 0.01;  ///< d < -this is drawn as penetration
};

inline constexpr Rgb8 kContactPenetrationColour = {200, 0, 200};
inline constexpr Rgb8 kContactFarColour = {226, 222, 210};
/// Distance stored for a vertex with no opposing surface within reach (as the report's).
inline constexpr float kContactFarValue = 1e6f;

/// Colour of signed distance d (mm) on the scale.
Rgb8 ContactColour(double d, const ContactScale& scale);

/// The ramp's stops as (fraction of max_mm, colour), first at 0, last at 1: a legend
/// drawn as linear segments between them shows exactly the ramp.
std::vector<std::pair<double, Rgb8>> ContactRampStops();

}  // namespace occlude::app
