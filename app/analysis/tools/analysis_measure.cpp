// Debug placeholder, replaced by the measurement program.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "analysis/arch_geometry.h"
#include "analysis/geometry_util.h"
#include "analysis/occlusal_plane.h"
#include "occlude/io/landmark_file.h"
#include "occlude/io/mesh_io.h"

using namespace occlude;

int main(int argc, char** argv) {
  if (argc < 4) return 2;
  const io::TriangleMesh mesh = io::LoadMesh(argv[1]);
  const io::Jaw jaw = std::string(argv[2]) == "upper" ? io::Jaw::kUpper : io::Jaw::kLower;
  std::vector<std::string> notes;
  std::string why;
  analysis::ArchAnalysisOptions options;
  const auto g = analysis::BuildArchGeometry(mesh, jaw, options, &notes, &why);
  for (auto& n : notes) std::printf("note: %s\n", n.c_str());
  if (!g) {
    std::printf("error: %s\n", why.c_str());
    return 1;
  }
  auto v = [](const Eigen::Vector3d& x) {
    return std::to_string(x.x()) + " " + std::to_string(x.y()) + " " + std::to_string(x.z());
  };
  std::printf("origin %s\nup %s\nanterior %s\nleft %s\nconf %.2f\n", v(g->axes.origin_J).c_str(),
              v(g->axes.up_J).c_str(), v(g->axes.e2_J).c_str(), v(g->axes.e1_J).c_str(),
              g->confidence);
  std::ofstream map(std::string(argv[3]) + "_map.csv");
  for (int c = 0; c < g->top.nx * g->top.ny; ++c) {
    if (!g->top.Filled(c)) continue;
    const auto q = g->top.Centre(c);
    const auto pr = g->curve.Project(q);
    map << q.x() << "," << q.y() << "," << g->top.height[c] << "," << pr.s << "," << pr.t << ","
        << g->crown[c] << "\n";
  }
  std::ofstream curve(std::string(argv[3]) + "_curve.csv");
  for (std::size_t k = 0; k < g->curve.q.size(); ++k) {
    curve << g->curve.q[k].x() << "," << g->curve.q[k].y() << "," << g->curve.top[k] << "\n";
  }
  if (argc > 4) {
    std::vector<Eigen::Vector3d> pts;
    for (const auto& l : io::ReadLandmarkFile(argv[4])) {
      if (l.jaw != jaw) continue;
      if (l.type == io::LandmarkType::kMesial || l.type == io::LandmarkType::kDistal ||
          l.type == io::LandmarkType::kFacial || l.type == io::LandmarkType::kLingual)
        continue;
      pts.push_back(l.p);
    }
    const auto pl = analysis::FitPlane(pts);
    std::printf("angle to landmark plane %.1f deg\n",
                std::acos(std::abs(pl.normal.dot(g->axes.up_J))) * 57.3);
    const auto op = analysis::FindOcclusalPlane(mesh, 0.2);
    std::printf("cusps %d rms %.2f conf %.2f\n", op.cusps, op.rms_mm, op.confidence);
  }
  std::printf("curve length %.1f apex %.1f\n", g->curve.Length(), g->curve.apex_s);
  return 0;
}
