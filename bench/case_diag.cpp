// Diagnoses a registered case: the arch frame, and the penetrating upper samples at the
// pose as given, grouped into patches (samples within 1 mm of each other), each patch with
// its deepest depth, area and centre; the same for the lower samples in the upper.
//   occlude_case_diag <case folder> [voxel_mm=0.4]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <numeric>

#include "occlude/collision/signed_distance.h"
#include "occlude/planner/plan.h"
#include "session/jaw_pair.h"

using namespace occlude;

// Boundary flag per sample: is its closest point on `mesh` on a boundary edge (or a vertex
// of one)? Brute force.
static std::vector<bool> OnBoundary(const io::TriangleMesh& mesh,
                                    const std::vector<collision::SurfacePoint>& pts,
                                    const Eigen::Isometry3d& X_meshFrame_ptsFrame) {
  std::map<std::pair<int, int>, int> edge_count;
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      int a = t[k], b = t[(k + 1) % 3];
      if (a > b) std::swap(a, b);
      ++edge_count[{a, b}];
    }
  }
  std::vector<bool> boundary_vertex(mesh.vertices.size(), false);
  for (const auto& [e, c] : edge_count) {
    if (c == 1) boundary_vertex[e.first] = boundary_vertex[e.second] = true;
  }
  collision::PseudoNormals normals(mesh);
  std::vector<bool> out;
  for (const auto& p : pts) {
    collision::SignedDistanceSample s;
    collision::SignedDistanceBruteForce(mesh, normals, X_meshFrame_ptsFrame * p.p_L, &s);
    const auto& t = mesh.triangles[s.triangle];
    bool on = false;
    for (int k = 0; k < 3; ++k) {
      if ((mesh.vertices[t[k]] - s.closest).norm() < 0.05 && boundary_vertex[t[k]]) on = true;
      int a = t[k], b = t[(k + 1) % 3];
      const Eigen::Vector3d A = mesh.vertices[a], B = mesh.vertices[b];
      const double u = std::clamp((s.closest - A).dot(B - A) / (B - A).squaredNorm(), 0.0, 1.0);
      if (a > b) std::swap(a, b);
      if ((A + u * (B - A) - s.closest).norm() < 1e-6 && edge_count[{a, b}] == 1) on = true;
    }
    out.push_back(on);
  }
  return out;
}

static void Patches(const std::vector<collision::SurfacePoint>& pts,
                    const std::vector<bool>& boundary) {
  const std::size_t n = pts.size();
  std::vector<int> comp(n, -1);
  int nc = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (comp[i] >= 0) continue;
    std::vector<std::size_t> stack{i};
    comp[i] = nc;
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      for (std::size_t j = 0; j < n; ++j) {
        if (comp[j] < 0 && (pts[j].p_L - pts[k].p_L).norm() < 1.0) {
          comp[j] = nc;
          stack.push_back(j);
        }
      }
    }
    ++nc;
  }
  struct P {
    double depth = 0, area = 0;
    int count = 0, on_boundary = 0;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
  };
  std::vector<P> ps(nc);
  for (std::size_t i = 0; i < n; ++i) {
    P& p = ps[comp[i]];
    p.depth = std::max(p.depth, -pts[i].distance_mm);
    p.area += pts[i].area_mm2;
    p.count++;
    p.on_boundary += boundary[i] ? 1 : 0;
    p.c += pts[i].p_L;
  }
  std::sort(ps.begin(), ps.end(), [](const P& a, const P& b) { return a.depth > b.depth; });
  for (const P& p : ps) {
    const Eigen::Vector3d c = p.c / p.count;
    std::printf(
        "  patch depth %.3f mm area %.3f mm2 samples %d (%d closest to a boundary) at (%.1f %.1f "
        "%.1f)\n",
        p.depth, p.area, p.count, p.on_boundary, c.x(), c.y(), c.z());
  }
}

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  const std::string dir = argv[1];
  const double voxel = argc > 2 ? std::atof(argv[2]) : 0.4;
  const app::JawPair jaws = app::LoadCaseFolder(dir);
  const auto& lower = jaws.lower_L;
  const auto& upper = jaws.upper_U;
  collision::OracleOptions o;
  o.voxel_size_mm = voxel;
  collision::JawOracle fwd(lower, upper, o), rev(upper, lower, o);
  const auto& a = fwd.arch();
  std::printf("occlusal (%.3f %.3f %.3f) anterior (%.3f %.3f %.3f)\n", a.occlusal_L.x(),
              a.occlusal_L.y(), a.occlusal_L.z(), a.anterior_L.x(), a.anterior_L.y(),
              a.anterior_L.z());
  collision::OracleRequest q;
  q.level = collision::AccuracyLevel::kExact;
  q.penetration_search_mm = 2.0;
  collision::OracleResult r;
  fwd.Query(Eigen::Isometry3d::Identity(), q, &r);
  std::printf("upper in lower: max %.3f area %.3f deep %zu contact %.2f mm2\n",
              r.max_penetration_mm, r.penetration_area_mm2, r.deep_samples, r.contact_area_mm2);
  Patches(r.penetrations, OnBoundary(*lower, r.penetrations, Eigen::Isometry3d::Identity()));
  rev.Query(Eigen::Isometry3d::Identity(), q, &r);
  std::printf("lower in upper: max %.3f area %.3f deep %zu contact %.2f mm2\n",
              r.max_penetration_mm, r.penetration_area_mm2, r.deep_samples, r.contact_area_mm2);
  Patches(r.penetrations, OnBoundary(*upper, r.penetrations, Eigen::Isometry3d::Identity()));
  return 0;
}
