// Finding the teeth (tooth_regions.h).
#include "tooth_regions.h"

#include <algorithm>
#include <numeric>

#include "geometry_util.h"
#include "tooth_segmentation.h"

namespace occlude::analysis {
namespace {

constexpr std::size_t kMinShellTriangles = 50;
constexpr double kMinToothExtentMm = 3.0, kMaxToothExtentMm = 16.0;  // across the plane
constexpr std::size_t kMinShellTeeth = 4;  // fewer tooth-like shells: segment instead
constexpr double kShellConfidence = 0.7;   // numbered by arch order only
constexpr double kCrownHalfWidthMm = 8.0;  // the crown band around the curve, for profiles
// A cut between two segmented crowns follows their valley within this reach of the boundary
// along the arch, and within this share of the narrower crown's width.
constexpr double kCutReachMm = 2.0, kCutReachShare = 0.3;

int Find(std::vector<int>& parent, int v) {
  while (parent[static_cast<std::size_t>(v)] != v) {
    parent[static_cast<std::size_t>(v)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    v = parent[static_cast<std::size_t>(v)];
  }
  return v;
}

// Median arc length and the plane extent of a set of triangles.
void ShellPlacement(const io::TriangleMesh& mesh, const ArchGeometry& g,
                    const std::vector<std::int32_t>& tris, double* s, double* extent) {
  std::vector<double> arc;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (const std::int32_t t : tris) {
    const auto v = static_cast<std::size_t>(mesh.triangles[static_cast<std::size_t>(t)][0]);
    arc.push_back(g.vertex_st[v].s);
    const Eigen::Vector2d q = g.axes.Plane(mesh.vertices[v]);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  *s = Quantile(arc, 0.5);
  *extent = (hi - lo).maxCoeff();
}

std::vector<ToothRegion> FromParts(const io::TriangleMesh& mesh, io::Jaw jaw,
                                   std::vector<std::string>* notes) {
  std::vector<ToothRegion> teeth;
  for (std::size_t p = 0; p < mesh.parts.size(); ++p) {
    const int universal = mesh.parts[p].tooth_number;
    if (universal < 1 || universal > 32) continue;
    const int fdi = io::FdiFromUniversal(universal);
    if (io::JawOfFdi(fdi) != jaw) {
      notes->push_back("part '" + mesh.parts[p].name + "' is tooth " + std::to_string(fdi) +
                       " of the other jaw; left out");
      continue;
    }
    ToothRegion r;
    r.fdi = fdi;
    r.source = ToothSource::kParts;
    r.confidence = 1.0;
    for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
      if (mesh.triangle_part[t] == static_cast<std::int32_t>(p))
        r.triangles.push_back(static_cast<std::int32_t>(t));
    }
    if (!r.triangles.empty()) teeth.push_back(std::move(r));
  }
  return teeth;
}

// Tooth-sized shells numbered outward from the arch's mirror axis on each side.
std::vector<ToothRegion> FromShells(const io::TriangleMesh& mesh, const ArchGeometry& g,
                                    io::Jaw jaw) {
  struct Shell {
    double s;
    std::vector<std::int32_t> tris;
  };
  std::vector<Shell> shells;
  for (auto& tris : Components(mesh)) {
    if (tris.size() < kMinShellTriangles) continue;
    double s = 0.0, extent = 0.0;
    ShellPlacement(mesh, g, tris, &s, &extent);
    if (extent < kMinToothExtentMm || extent > kMaxToothExtentMm) continue;
    shells.push_back({s, std::move(tris)});
  }
  if (shells.size() < kMinShellTeeth) return {};
  std::sort(shells.begin(), shells.end(), [](const Shell& a, const Shell& b) { return a.s < b.s; });
  const auto mid = std::lower_bound(shells.begin(), shells.end(), g.curve.symmetry_s,
                                    [](const Shell& a, double s) { return a.s < s; });
  const long right = mid - shells.begin();
  std::vector<ToothRegion> teeth;
  for (long i = 0; i < static_cast<long>(shells.size()); ++i) {
    const bool is_right = i < right;
    const long position = is_right ? right - i : i - right + 1;
    if (position > 8) continue;
    const int quadrant = jaw == io::Jaw::kUpper ? (is_right ? 1 : 2) : (is_right ? 4 : 3);
    ToothRegion r;
    r.fdi = 10 * quadrant + static_cast<int>(position);
    r.source = ToothSource::kComponents;
    r.confidence = kShellConfidence;
    r.triangles = std::move(shells[static_cast<std::size_t>(i)].tris);
    teeth.push_back(std::move(r));
  }
  return teeth;
}

// The cuts of segmented teeth (right to left, neighbours sharing their boundaries): the valley
// between neighbours, straight cuts at the arch's two ends.
void CutBetweenCrowns(const ArchGeometry& g, std::vector<ToothRegion>* teeth) {
  for (std::size_t k = 0; k < teeth->size(); ++k) {
    ToothRegion& r = (*teeth)[k];
    if (k == 0) r.right_cut = StraightCut(r.s_lo);
    if (k + 1 == teeth->size()) {
      r.left_cut = StraightCut(r.s_hi);
      continue;
    }
    ToothRegion& next = (*teeth)[k + 1];
    const double narrower = std::min(r.s_hi - r.s_lo, next.s_hi - next.s_lo);
    r.left_cut = FindToothCut(g, r.s_hi, std::min(kCutReachMm, kCutReachShare * narrower));
    next.right_cut = r.left_cut;
    r.s_hi = next.s_lo = r.left_cut.At(0.0);
  }
}

}  // namespace

std::vector<std::vector<std::int32_t>> Components(const io::TriangleMesh& mesh) {
  std::vector<int> parent(mesh.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& t : mesh.triangles) {
    const int a = Find(parent, t[0]);
    parent[static_cast<std::size_t>(Find(parent, t[1]))] = a;
    parent[static_cast<std::size_t>(Find(parent, t[2]))] = a;
  }
  std::vector<int> index(mesh.num_vertices(), -1);
  std::vector<std::vector<std::int32_t>> out;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto root = static_cast<std::size_t>(Find(parent, mesh.triangles[t][0]));
    if (index[root] < 0) {
      index[root] = static_cast<int>(out.size());
      out.emplace_back();
    }
    out[static_cast<std::size_t>(index[root])].push_back(static_cast<std::int32_t>(t));
  }
  return out;
}

std::vector<ToothRegion> FindTeeth(const io::TriangleMesh& mesh, const ArchGeometry& g, io::Jaw jaw,
                                   std::vector<std::string>* notes, std::string* why) {
  std::vector<ToothRegion> teeth = FromParts(mesh, jaw, notes);
  if (teeth.empty()) teeth = FromShells(mesh, g, jaw);
  if (teeth.empty()) {
    const CrownProfile profile =
        MakeCrownProfile(g.top, g.crown, g.cell_st, g.curve, g.crown_floor, kCrownHalfWidthMm);
    for (const ToothSpan& span : SegmentTeeth(profile, g.curve, jaw, why)) {
      ToothRegion r;
      r.fdi = span.fdi;
      r.s_lo = span.s_lo;
      r.s_hi = span.s_hi;
      r.confidence = span.confidence;
      teeth.push_back(std::move(r));
    }
    CutBetweenCrowns(g, &teeth);
  }
  // Right to left: the right side's teeth from the back, then the left side's from the front.
  std::sort(teeth.begin(), teeth.end(), [](const ToothRegion& a, const ToothRegion& b) {
    const auto key = [](int fdi) {
      return io::IsLeftSide(fdi) ? io::ToothPosition(fdi) : -io::ToothPosition(fdi);
    };
    return key(a.fdi) < key(b.fdi);
  });
  return teeth;
}

}  // namespace occlude::analysis
