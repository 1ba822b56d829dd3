// The contact map's colour conventions (see docs/domain.md): signed distance to
// the opposing arch on a fixed mm scale, red (tight contact) through orange,
// yellow and green to blue (open, at map_max_mm); farther surface in a neutral
// ivory; penetration deeper than `penetration_from_mm` in magenta, a colour the
// ramp never uses. Every image carries the mm legend.
#pragma once

#include <cmath>

#include "report/render_raster.h"
#include "viewer/contact_colours.h"

namespace occlude::app::render {

struct MapScale {
  double max_mm = 0.5;                ///< colour ramp 0..max_mm
  double band_mm = 0.1;               ///< contact band (0 <= d <= band), marked on the legend
  double penetration_from_mm = 0.01;  ///< d < -this is drawn as penetration
};

inline constexpr Rgb kPenetrationColour = kContactPenetrationColour;
inline constexpr Rgb kFarColour = kContactFarColour;
inline constexpr Rgb kBackground = {255, 255, 255};
/// Value stored for a vertex with no opposing surface within reach.
inline constexpr float kFarValue = kContactFarValue;

/// Colour of signed distance d (mm) on the scale: the viewer's ramp (viewer/contact_colours.h),
/// so the still images and the 3D view agree.
Rgb DistanceColour(double d, const MapScale& scale);

/// Hue in degrees [0, 360), saturation and value in [0, 1].
void ToHsv(Rgb c, double* hue, double* saturation, double* value);
/// A (possibly shaded) pixel of the contact colours (0 <= d <= band with the
/// default scale: hue within 0-32 degrees, saturated).
bool IsContactColour(Rgb c);
/// A (possibly shaded) pixel of the penetration colour.
bool IsPenetrationColour(Rgb c);

}  // namespace occlude::app::render
