// Pi and the degree-radian conversions of the project, defined once (in io, the bottom of the
// dependency chain, beside clock.h, so that every target sees them). Configs, reports and
// tables speak degrees; Eigen and the solvers speak radians.
#pragma once

namespace occlude {

/// Pi to double precision (the value of M_PI, without relying on a POSIX macro).
inline constexpr double kPi = 3.14159265358979323846;

/// Degrees to radians: deg * pi / 180 (in that order, so results do not depend on the caller).
constexpr double RadiansFromDegrees(double deg) { return deg * kPi / 180.0; }

/// Radians to degrees: rad * 180 / pi.
constexpr double DegreesFromRadians(double rad) { return rad * 180.0 / kPi; }

}  // namespace occlude
