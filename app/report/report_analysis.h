// The numbers behind a report at one pose: the oracle's contact and penetration
// totals, contact spots (clusters of contact samples) with the upper and lower
// tooth each lies on, per-tooth totals for both arches, and the signed distance
// of every vertex of each arch to the opposing arch (for the colour maps), and the clinical
// relationships (../shared/docs/clinical.md) of the session's arch analysis at the pose.
//
// Frames and units: X_LU as everywhere (upper mesh frame U in L), points in L,
// mm and mm^2. Vertex distances are exact (closest triangle, pseudo-normal sign)
// up to `reach_mm`; farther vertices (or deeper penetrations) hold kFarValue.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "analysis/relationships.h"
#include "config/case_config.h"
#include "occlude/collision/memory_estimate.h"
#include "occlude/collision/oracle.h"
#include "session/case_session.h"
#include "session/jaw_pair.h"

namespace occlude::app {

struct ContactSpot {
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();  ///< area-weighted centroid
  double area_mm2 = 0.0;
  std::size_t samples = 0;
  int upper_tooth = 0;  ///< Universal number, 0 = not a tooth / unknown
  int lower_tooth = 0;
};

struct ToothRow {
  int tooth = 0;  ///< Universal 1..32
  bool upper = true;
  double contact_area_mm2 = 0.0;
  int spots = 0;
  double penetration_area_mm2 = 0.0;
  double max_penetration_mm = 0.0;
};

struct ReportAnalysis {
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
  Eigen::Vector3d pivot_L =
      Eigen::Vector3d::Zero();     ///< pivot at X_LU (centre of the upper occlusal surface)
  planner::PoseParameters params;  ///< X_LU about the pivot relative to the jaws as given
  collision::ArchFrame arch;
  collision::OracleResult oracle;
  double voxel_mm = 0.0;
  std::vector<ContactSpot> spots;
  std::vector<ToothRow> teeth;         ///< every tooth of both arches, upper first, by number
  std::vector<float> lower_vertex_mm;  ///< per lower vertex: signed distance to the upper at X_LU
  std::vector<float> upper_vertex_mm;  ///< per upper vertex: signed distance to the lower
  double reach_mm = 1.0;
  std::vector<std::pair<std::string, double>> timings_s;  ///< step -> wall seconds
  std::vector<OracleModel>
      models;  ///< the session's oracles (region of interest, bytes, build time)
  analysis::Relationships relationships;  ///< clinical relationships at X_LU (session Analysis())
};

/// Evaluates the pose on the session's finest oracle and map fields (built on first use:
/// throws UserError when the voxel size does not fit the jaws).
ReportAnalysis AnalyzePose(CaseSession& session, const Eigen::Isometry3d& X_LU);

/// AnalyzePose at each of `poses` (in their order): the session's models for them first (the
/// finest oracle valid at each, the map fields, the arch analysis), then the poses two at a time
/// on threads of their own, which only read the session.
std::vector<ReportAnalysis> AnalyzePoses(CaseSession& session,
                                         const std::vector<Eigen::Isometry3d>& poses);

/// Groups points closer than `link_mm` (single linkage); returns a cluster id per point.
std::vector<int> ClusterPoints(const std::vector<Eigen::Vector3d>& points, double link_mm);

}  // namespace occlude::app
