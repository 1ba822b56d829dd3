// The arch curve of one jaw in its occlusal plane: the middle of the crown band, from the
// patient's right end to the left end, found ray by ray from a centre inside the U (each ray
// from it crosses the band once), smoothed and resampled at a fixed arc-length step. Points
// project onto it as (s, t): arc length s along it (0 at the right end, mm) and the signed
// distance t across it, t > 0 outward (buccal / labial).
//
// Coordinates: the plane coordinates of the height map it was fitted on, whose e1 is lateral
// (to the patient's left) and e2 anterior; heights along the occlusal axis from the plane.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "height_map.h"

namespace occlude::analysis {

struct ArchCurve {
  double step = 0.25;                ///< mm between stations
  std::vector<Eigen::Vector2d> q;    ///< stations, right to left, plane coordinates
  std::vector<double> top;           ///< height of the crowns' top at each station
  Eigen::Vector2d centre{0.0, 0.0};  ///< the centre the rays start from
  std::vector<double> angle;         ///< polar angle of each station about the centre (decreasing)
  double apex_s = 0.0;               ///< arc length of the most anterior station
  /// Arc length of the arch's mirror axis: the station about which points at equal arc length
  /// on both sides (3-15 mm away) lie at equal anterior coordinates; near the apex.
  double symmetry_s = 0.0;

  double Length() const { return q.size() < 2 ? 0.0 : step * static_cast<double>(q.size() - 1); }
  Eigen::Vector2d At(double s) const;
  Eigen::Vector2d Tangent(double s) const;  ///< unit, right to left
  Eigen::Vector2d Normal(double s) const;   ///< unit, outward
  double TopAt(double s) const;

  struct Projection {
    double s = 0.0;  ///< mm, beyond [0, Length()] past the ends (along the end tangents)
    double t = 0.0;  ///< mm, outward positive
  };
  Projection Project(const Eigen::Vector2d& p) const;
};

/// Polar angle of p about c: 0 anterior (+e2), positive towards the patient's right (-e1),
/// in (-pi, pi]; the cut lies directly posterior, in the U's opening.
double ArchAngle(const Eigen::Vector2d& c, const Eigen::Vector2d& p);

/// Fits the curve to the crown cells of `map` (cells of positive `crown` weight, CrownWeights)
/// around `centre`; nullopt with `why` when too little of a band is found.
std::optional<ArchCurve> FitArchCurve(const HeightMap& map, const std::vector<double>& crown,
                                      const Eigen::Vector2d& centre, double step, std::string* why);

}  // namespace occlude::analysis
