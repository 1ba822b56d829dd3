// Numbers as text for the CSV files, summaries and reports the commands write: one place for
// the fixed-decimal and shortest forms, so every output formats alike.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace occlude::app {

/// `v` with `digits` decimals (printf "%.*f": non-finite values print as nan / inf).
inline std::string Fixed(double v, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

/// Fixed(v, digits), or "" when v is not finite (an empty CSV cell).
inline std::string FixedOrEmpty(double v, int digits) {
  return std::isfinite(v) ? Fixed(v, digits) : "";
}

/// The shortest form (printf "%g"): 0.2, 1e-05, 100.
inline std::string ShortNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace occlude::app
