// The region of interest of a case session's search (see session_region.h).
#include "session/session_region.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace occlude::app {

double MapReachMm(const CaseConfig& config) {
  return std::max(1.0, config.report.map_max_mm + 0.25);
}

double SessionReadRadiusMm(const CaseConfig& config, const collision::OracleOptions& stage) {
  const double planner_reach = std::max({0.3, 4.0 * config.max_penetration_mm, 1.0});
  const double report_reach = MapReachMm(config);
  return collision::OracleReadRadiusMm(
      stage, std::max({config.contact_band_mm, planner_reach, report_reach}));
}

collision::RegionOfInterestRequest SessionRegionRequest(const CaseConfig& config,
                                                        const Eigen::Isometry3d& X_LU_start,
                                                        const Eigen::Vector3d& pivot_L,
                                                        double band_mm) {
  collision::RegionOfInterestRequest r;
  r.X_LU_start = X_LU_start;
  r.pivot_L = pivot_L;
  for (std::size_t d = 0; d < 6; ++d) {
    r.bound_min[d] = config.bounds[d].min;
    r.bound_max[d] = config.bounds[d].max;
    r.locked[d] = config.locked[d];
  }
  r.band_mm = band_mm;
  return r;
}

std::string RegionLine(double voxel_mm, const collision::RegionOfInterestStats& s) {
  auto share = [](std::size_t kept, std::size_t total) {
    return total == 0 ? 100.0 : 100.0 * static_cast<double>(kept) / static_cast<double>(total);
  };
  std::ostringstream o;
  o << std::fixed << std::setprecision(1) << "region of interest for the " << voxel_mm
    << " mm oracle: " << share(s.lower_kept, s.lower_total) << " % of the lower's triangles ("
    << s.lower_kept << " of " << s.lower_total << ") and " << share(s.upper_kept, s.upper_total)
    << " % of the upper's (" << s.upper_kept << " of " << s.upper_total << ") are within reach "
    << s.reach_mm << " mm (read band " << s.band_mm << " + displacement over the bounds "
    << s.displacement_mm << ") of the other jaw";
  return o.str();
}

}  // namespace occlude::app
