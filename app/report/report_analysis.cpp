// Evaluating a pose for the report (see report_analysis.h).
#include "report/report_analysis.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <thread>
#include <unordered_map>

#include "base/tasks.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "occlude/collision/signed_distance.h"
#include "occlude/collision/voxel_grid.h"
#include "report/report_colours.h"

namespace occlude::app {
namespace {

// Contact samples closer than this belong to one spot (samples are ~0.3 mm apart).
constexpr double kSpotLinkMm = 0.6;

// Signed distance of every vertex (moved into the field's frame by X_FM) to the field's mesh;
// vertices farther than the near cells' reach (culled by them first) hold kFarValue.
std::vector<float> VertexDistances(const io::TriangleMesh& mesh, const Eigen::Isometry3d& X_FM,
                                   const collision::NarrowBandSdf& field,
                                   const NearCells& near_cells) {
  std::vector<float> out(mesh.num_vertices(), render::kFarValue);
  const double reach = near_cells.reach_mm();
  const std::size_t threads = std::clamp<std::size_t>(std::thread::hardware_concurrency(), 1, 4);
  const std::size_t chunk = (out.size() + threads - 1) / threads;
  std::vector<std::thread> pool;
  for (std::size_t k = 0; k < threads; ++k) {
    pool.emplace_back([&, k] {
      collision::SignedDistanceSample s;
      for (std::size_t i = k * chunk; i < std::min(out.size(), (k + 1) * chunk); ++i) {
        const Eigen::Vector3d p = X_FM * mesh.vertices[i];
        if (near_cells.Near(p) && field.Exact(p, reach, &s))
          out[i] = static_cast<float>(s.distance);
      }
    });
  }
  for (auto& t : pool) t.join();
  return out;
}

int ToothOfTriangle(const io::TriangleMesh& mesh, std::uint32_t t) {
  if (mesh.triangle_part.empty()) return 0;
  const auto part = static_cast<std::size_t>(mesh.triangle_part[t]);
  return part < mesh.parts.size() ? mesh.parts[part].tooth_number : 0;
}

int ToothOfPart(const io::TriangleMesh& mesh, std::int32_t part) {
  const auto p = static_cast<std::size_t>(part);
  return p < mesh.parts.size() ? mesh.parts[p].tooth_number : 0;
}

// Lower tooth under a point of the interface (0 when none within reach).
int LowerToothAt(const collision::NarrowBandSdf& lower_field, const io::TriangleMesh& lower,
                 const Eigen::Vector3d& p_L, double reach) {
  collision::SignedDistanceSample s;
  return lower_field.Exact(p_L, reach, &s) ? ToothOfTriangle(lower, s.triangle) : 0;
}

std::vector<ToothRow> ToothRows(const JawPair& jaws) {
  std::vector<ToothRow> rows;
  for (const auto* mesh : {jaws.upper_U.get(), jaws.lower_L.get()}) {
    for (const auto& part : mesh->parts) {
      if (part.tooth_number > 0) rows.push_back({part.tooth_number, mesh == jaws.upper_U.get()});
    }
  }
  std::sort(rows.begin(), rows.end(), [](const ToothRow& a, const ToothRow& b) {
    return a.upper != b.upper ? a.upper : a.tooth < b.tooth;
  });
  rows.erase(std::unique(rows.begin(), rows.end(),
                         [](const ToothRow& a, const ToothRow& b) {
                           return a.tooth == b.tooth && a.upper == b.upper;
                         }),
             rows.end());
  return rows;
}

ToothRow* FindRow(std::vector<ToothRow>* rows, int tooth, bool upper) {
  for (auto& r : *rows) {
    if (r.tooth == tooth && r.upper == upper) return &r;
  }
  return nullptr;
}

// Spots and per-tooth totals from the oracle's contact and penetration samples.
void Attribute(const JawPair& jaws, const collision::NarrowBandSdf& lower_field,
               ReportAnalysis* a) {
  const auto& contacts = a->oracle.contacts;
  std::vector<Eigen::Vector3d> points;
  std::vector<int> lower_tooth(contacts.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    points.push_back(contacts[i].p_L);
    lower_tooth[i] = LowerToothAt(lower_field, *jaws.lower_L, contacts[i].p_L, a->reach_mm);
  }
  const std::vector<int> cluster = ClusterPoints(points, kSpotLinkMm);
  const int n = cluster.empty() ? 0 : *std::max_element(cluster.begin(), cluster.end()) + 1;
  std::vector<ContactSpot> spots(static_cast<std::size_t>(n));
  std::vector<std::map<int, double>> upper_votes(spots.size()), lower_votes(spots.size());
  a->teeth = ToothRows(jaws);
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const auto c = static_cast<std::size_t>(cluster[i]);
    const double w = contacts[i].area_mm2;
    spots[c].p_L += w * contacts[i].p_L;
    spots[c].area_mm2 += w;
    ++spots[c].samples;
    const int ut = ToothOfPart(*jaws.upper_U, contacts[i].part);
    upper_votes[c][ut] += w;
    lower_votes[c][lower_tooth[i]] += w;
    if (ToothRow* r = FindRow(&a->teeth, ut, true)) r->contact_area_mm2 += w;
    if (ToothRow* r = FindRow(&a->teeth, lower_tooth[i], false)) r->contact_area_mm2 += w;
  }
  const auto majority = [](const std::map<int, double>& votes) {
    return std::max_element(votes.begin(), votes.end(),
                            [](const auto& x, const auto& y) { return x.second < y.second; })
        ->first;
  };
  for (std::size_t c = 0; c < spots.size(); ++c) {
    if (spots[c].area_mm2 > 0) spots[c].p_L /= spots[c].area_mm2;
    spots[c].upper_tooth = majority(upper_votes[c]);
    spots[c].lower_tooth = majority(lower_votes[c]);
    if (ToothRow* r = FindRow(&a->teeth, spots[c].upper_tooth, true)) ++r->spots;
    if (ToothRow* r = FindRow(&a->teeth, spots[c].lower_tooth, false)) ++r->spots;
  }
  a->spots = std::move(spots);
  for (const auto& p : a->oracle.penetrations) {
    const double depth = -p.distance_mm;
    for (ToothRow* r :
         {FindRow(&a->teeth, ToothOfPart(*jaws.upper_U, p.part), true),
          FindRow(&a->teeth, LowerToothAt(lower_field, *jaws.lower_L, p.p_L, a->reach_mm),
                  false)}) {
      if (r == nullptr) continue;
      r->penetration_area_mm2 += p.area_mm2;
      r->max_penetration_mm = std::max(r->max_penetration_mm, depth);
    }
  }
}

}  // namespace

std::vector<int> ClusterPoints(const std::vector<Eigen::Vector3d>& points, double link_mm) {
  std::vector<int> parent(points.size());
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  const auto find = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x) {
      parent[static_cast<std::size_t>(x)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
      x = parent[static_cast<std::size_t>(x)];
    }
    return x;
  };
  const auto key = [](long x, long y, long z) {
    return (static_cast<std::uint64_t>(x & 0x1fffff) << 42) |
           (static_cast<std::uint64_t>(y & 0x1fffff) << 21) |
           static_cast<std::uint64_t>(z & 0x1fffff);
  };
  std::unordered_map<std::uint64_t, std::vector<int>> cells;
  std::vector<Eigen::Vector3i> cell_of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    cell_of[i] = (points[i] / link_mm).array().floor().cast<int>();
    cells[key(cell_of[i].x(), cell_of[i].y(), cell_of[i].z())].push_back(static_cast<int>(i));
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it =
              cells.find(key(cell_of[i].x() + dx, cell_of[i].y() + dy, cell_of[i].z() + dz));
          if (it == cells.end()) continue;
          for (const int j : it->second) {
            if ((points[i] - points[static_cast<std::size_t>(j)]).norm() < link_mm) {
              parent[static_cast<std::size_t>(find(static_cast<int>(i)))] = find(j);
            }
          }
        }
      }
    }
  }
  std::unordered_map<int, int> ids;
  std::vector<int> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int root = find(static_cast<int>(i));
    const auto it = ids.emplace(root, static_cast<int>(ids.size())).first;
    out[i] = it->second;
  }
  return out;
}

ReportAnalysis AnalyzePose(CaseSession& session, const Eigen::Isometry3d& X_LU) {
  const CaseConfig& config = session.config();
  const JawPair& jaws = session.jaws();
  ReportAnalysis a;
  a.X_LU = X_LU;
  a.voxel_mm = config.VoxelSizeMm();
  a.reach_mm = MapReachMm(config);
  a.arch = session.arch();
  // Parameters about the pivot at the pose as given (U = L there), relative to it.
  a.pivot_L = X_LU * session.pivot_L();
  a.params = planner::DecomposePose(X_LU, session.pivot_L(), Eigen::Isometry3d::Identity());

  double t0 = NowSeconds();
  const collision::JawOracle& oracle = session.FinestOracleAt(X_LU);
  const MapFields& maps = session.Maps();
  a.timings_s.emplace_back("models (built once per session)", NowSeconds() - t0);
  a.models = session.Models();

  t0 = NowSeconds();
  collision::OracleRequest request;
  // The level chosen for the accuracy, but never the voxel level for a report.
  request.level = config.OracleLevel() == collision::AccuracyLevel::kExact
                      ? collision::AccuracyLevel::kExact
                      : collision::AccuracyLevel::kSubVoxel;
  request.contact_band_mm = config.contact_band_mm;
  request.penetration_search_mm = a.reach_mm;
  request.pivot_L = a.pivot_L;
  oracle.Query(X_LU, request, &a.oracle);
  a.timings_s.emplace_back("oracle query", NowSeconds() - t0);

  t0 = NowSeconds();
  a.upper_vertex_mm = VertexDistances(*jaws.upper_U, X_LU, maps.lower(), maps.lower_near);
  a.lower_vertex_mm = VertexDistances(*jaws.lower_L, X_LU.inverse(), maps.upper(), maps.upper_near);
  Attribute(jaws, maps.lower(), &a);
  a.timings_s.emplace_back("map distances", NowSeconds() - t0);

  t0 = NowSeconds();
  a.relationships = RelationshipsAt(session.Analysis(), X_LU);
  a.timings_s.emplace_back("clinical relationships (arch analysis once per session)",
                           NowSeconds() - t0);
  return a;
}

std::vector<ReportAnalysis> AnalyzePoses(CaseSession& session,
                                         const std::vector<Eigen::Isometry3d>& poses) {
  // What AnalyzePose builds on first use, built here first: the tasks below then only read the
  // session.
  for (const Eigen::Isometry3d& X_LU : poses) session.FinestOracleAt(X_LU);
  session.Maps();
  session.Analysis();
  std::vector<ReportAnalysis> out(poses.size());
  std::vector<std::function<void()>> tasks;
  for (std::size_t i = 0; i < poses.size(); ++i)
    tasks.emplace_back([&, i] { out[i] = AnalyzePose(session, poses[i]); });
  RunTasks(tasks);
  return out;
}

}  // namespace occlude::app
