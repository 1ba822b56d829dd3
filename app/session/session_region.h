// The region of interest of a case session's search (collision/region_of_interest.h): what the
// session asks for (the config's start pose, pivot and bounds, and the band each oracle of the
// schedule reads), and how the oracles it built are reported (stderr, metrics.json settings).
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string>

#include "config/case_config.h"
#include "occlude/collision/oracle.h"
#include "occlude/collision/region_of_interest.h"

namespace occlude::app {

/// One contact oracle a session built: on the region of interest (`region` set) or on the
/// whole jaws. Bytes are JawOracle::MemoryBytes, seconds its wall build time (plus the
/// region's selection when on).
struct OracleModel {
  double voxel_mm = 0.0;
  std::optional<collision::RegionOfInterestStats> region;
  std::size_t bytes = 0;
  double build_seconds = 0.0;
  bool lower_cut = false, upper_cut = false;  ///< modelled on the region's sub-mesh (else whole)
};

/// How far from the other jaw the report's vertex maps hold exact distances: max(1, map_max_mm +
/// 0.25) (a vertex farther away holds the far value).
double MapReachMm(const CaseConfig& config);

/// The farthest the session's queries read the lower jaw around an upper point on an oracle
/// built with `stage` (collision::OracleReadRadiusMm), for the widest exact-level reach any of
/// them asks for: the contact band, the planner's penetration search (max(0.3, 4 x
/// max_penetration_mm)) and its seat window (1 mm), and the report's map reach
/// (MapReachMm).
double SessionReadRadiusMm(const CaseConfig& config, const collision::OracleOptions& stage);

/// The region request of a search from X_LU_start (pivot_L at that pose) within the config's
/// bounds and locks, for an oracle reading `band_mm`.
collision::RegionOfInterestRequest SessionRegionRequest(const CaseConfig& config,
                                                        const Eigen::Isometry3d& X_LU_start,
                                                        const Eigen::Vector3d& pivot_L,
                                                        double band_mm);

/// "region of interest for the 0.2 mm oracle: 41 % of the lower's triangles (...) and ..."
std::string RegionLine(double voxel_mm, const collision::RegionOfInterestStats& stats);

}  // namespace occlude::app
