// Evaluating a pose for the report (see report_analysis.h).
#include "report/report_analysis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include "base/timing.h"
#include "base/user_error.h"
#include "occlude/collision/signed_distance.h"
#include "occlude/collision/voxel_grid.h"
#include "report/report_colours.h"

namespace occlude::app {
namespace {

// Contact samples closer than this belong to one spot (samples are ~0.3 mm apart).
constexpr double kSpotLinkMm = 0.6;

std::uint64_t CellKey(const Eigen::Vector3i& c) {
  auto u = [](int v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff; };
  return (u(c.x()) << 42) | (u(c.y()) << 21) | u(c.z());
}

Eigen::Vector3i CellOf(const Eigen::Vector3d& p, double cell) {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / cell)),
                         static_cast<int>(std::floor(p.y() / cell)),
                         static_cast<int>(std::floor(p.z() / cell)));
}

// Where a point may lie within `reach` of a mesh: the cells within `grow` cells (per axis) of a
// cell that the bounding box of one of the mesh's triangles touches, with grow * cell >= reach
// (a point whose cell is not among them is farther than `reach`). Cells of half the reach grown
// by two, in a bitmap over the mesh's box of cells (grown by two; the boxes marked, then dilated
// one axis at a time): a thinner shell of candidates than cells of the reach grown by one (on
// a-bite's jaws a third fewer of the vertices that Exact searches the whole reach for in vain).
// When that bitmap would be huge (a stray vertex far away), cells of the reach grown by one in a
// hash set.
class NearCells {
 public:
  NearCells(const io::TriangleMesh& mesh, double reach) {
    std::vector<std::pair<Eigen::Vector3i, Eigen::Vector3i>> boxes;
    Eigen::Vector3i hi;
    grow_ = 2;
    cell_ = reach * (1.0 + 1e-9) / grow_;
    Boxes(mesh, &boxes, &hi);
    if (boxes.empty()) return;
    lo_ -= Eigen::Vector3i::Constant(grow_);  // room for the dilation
    dims_ = (hi - lo_ + Eigen::Vector3i::Constant(1 + grow_)).cast<std::int64_t>();
    if (dims_.prod() > kMaxBitmapCells) {
      grow_ = 1;
      cell_ = reach * (1.0 + 1e-9);
      Boxes(mesh, &boxes, &hi);
      const Eigen::Vector3i g = Eigen::Vector3i::Constant(grow_);
      for (const auto& [l, h] : boxes)
        ForCells(l - g, h + g, [&](const Eigen::Vector3i& c) { set_.insert(CellKey(c)); });
      return;
    }
    bits_.assign(static_cast<std::size_t>(dims_.prod()), 0);
    for (const auto& [l, h] : boxes)
      ForCells(l, h, [&](const Eigen::Vector3i& c) { bits_[At(c)] = 1; });
    for (int axis = 0; axis < 3; ++axis) {
      for (int step = 0; step < grow_; ++step) Dilate(axis);
    }
  }

  /// False: p is farther than the reach from the mesh.
  bool Near(const Eigen::Vector3d& p) const { return Contains(CellOf(p, cell_)); }

 private:
  static constexpr std::int64_t kMaxBitmapCells = std::int64_t{1} << 26;

  // Each triangle's box of cells (of cell_), and the box of them all (lo_, *hi).
  void Boxes(const io::TriangleMesh& mesh,
             std::vector<std::pair<Eigen::Vector3i, Eigen::Vector3i>>* boxes, Eigen::Vector3i* hi) {
    boxes->resize(mesh.num_triangles());
    lo_ = Eigen::Vector3i::Constant(std::numeric_limits<int>::max());
    *hi = Eigen::Vector3i::Constant(std::numeric_limits<int>::min());
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      const Eigen::Vector3d a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
      (*boxes)[t] = {CellOf(a.cwiseMin(b).cwiseMin(c), cell_),
                     CellOf(a.cwiseMax(b).cwiseMax(c), cell_)};
      lo_ = lo_.cwiseMin((*boxes)[t].first);
      *hi = hi->cwiseMax((*boxes)[t].second);
    }
  }

  bool Contains(const Eigen::Vector3i& c) const {
    if (bits_.empty()) return set_.count(CellKey(c)) > 0;
    const Eigen::Vector3i i = c - lo_;
    if ((i.array() < 0).any() || (i.cast<std::int64_t>().array() >= dims_.array()).any())
      return false;
    return bits_[At(c)] != 0;
  }

  template <typename Visit>
  static void ForCells(const Eigen::Vector3i& l, const Eigen::Vector3i& h, Visit&& visit) {
    for (int x = l.x(); x <= h.x(); ++x) {
      for (int y = l.y(); y <= h.y(); ++y) {
        for (int z = l.z(); z <= h.z(); ++z) visit(Eigen::Vector3i(x, y, z));
      }
    }
  }
  std::size_t At(const Eigen::Vector3i& c) const {
    const Eigen::Matrix<std::int64_t, 3, 1> i = (c - lo_).cast<std::int64_t>();
    return static_cast<std::size_t>(i.x() + dims_.x() * (i.y() + dims_.y() * i.z()));
  }
  // Every cell also marked when a neighbour along `axis` is: each line of cells along the axis
  // ORs in the lines before and after it (the box was grown by grow_, so nothing marked
  // reaches its border).
  void Dilate(int axis) {
    const auto stride = static_cast<std::size_t>(axis == 0   ? 1
                                                 : axis == 1 ? dims_.x()
                                                             : dims_.x() * dims_.y());
    const auto n = static_cast<std::size_t>(dims_[axis]);
    const std::size_t outer = bits_.size() / (stride * n);
    const std::vector<std::uint8_t> before = bits_;
    for (std::size_t o = 0; o < outer; ++o) {
      for (std::size_t a = 0; a < n; ++a) {
        const std::size_t line = (o * n + a) * stride;
        std::uint8_t* out = &bits_[line];
        if (a > 0) {
          const std::uint8_t* prev = &before[line - stride];
          for (std::size_t k = 0; k < stride; ++k) out[k] |= prev[k];
        }
        if (a + 1 < n) {
          const std::uint8_t* next = &before[line + stride];
          for (std::size_t k = 0; k < stride; ++k) out[k] |= next[k];
        }
      }
    }
  }

  double cell_ = 1.0;
  int grow_ = 1;
  Eigen::Vector3i lo_ = Eigen::Vector3i::Zero();
  Eigen::Matrix<std::int64_t, 3, 1> dims_ = Eigen::Matrix<std::int64_t, 3, 1>::Zero();
  std::vector<std::uint8_t> bits_;
  std::unordered_set<std::uint64_t> set_;
};

// Signed distance of every vertex (moved into the field's frame by X_FM) to the field's mesh;
// vertices farther than `reach` (culled by the near cells first) hold kFarValue.
std::vector<float> VertexDistances(const io::TriangleMesh& mesh, const Eigen::Isometry3d& X_FM,
                                   const collision::NarrowBandSdf& field,
                                   const io::TriangleMesh& field_mesh, double reach) {
  std::vector<float> out(mesh.num_vertices(), render::kFarValue);
  const NearCells near_cells(field_mesh, reach);
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
  a.reach_mm = std::max(1.0, config.report.map_max_mm + 0.25);
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
  a.upper_vertex_mm = VertexDistances(*jaws.upper_U, X_LU, maps.lower(), *jaws.lower_L, a.reach_mm);
  a.lower_vertex_mm =
      VertexDistances(*jaws.lower_L, X_LU.inverse(), maps.upper(), *jaws.upper_U, a.reach_mm);
  Attribute(jaws, maps.lower(), &a);
  a.timings_s.emplace_back("map distances", NowSeconds() - t0);

  t0 = NowSeconds();
  a.relationships = RelationshipsAt(session.Analysis(), X_LU);
  a.timings_s.emplace_back("clinical relationships (arch analysis once per session)",
                           NowSeconds() - t0);
  return a;
}

}  // namespace occlude::app
