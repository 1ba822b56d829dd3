// render_measure CONFIG [--reps N] [--pose pose.json] [--only NAME]: the report's four pictures of
// a case at a pose (default: the config's start pose), each rendered and PNG-encoded N times on one
// thread; prints per picture the median thread CPU time and a checksum of its PNG (a change of the
// rasterizer that keeps the checksums keeps the pictures byte for byte).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "base/timing.h"
#include "config/case_config.h"
#include "config/pose_file.h"
#include "report/report_analysis.h"
#include "report/report_images.h"
#include "session/case_session.h"

namespace {

std::uint64_t Fnv1a(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace occlude::app;
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: render_measure CONFIG [--reps N] [--pose pose.json] [--only NAME]\n");
    return 2;
  }
  int reps = 5;
  std::string pose_file, only;
  for (int i = 2; i < argc; i += 2) {
    const std::string flag = argv[i];
    if (i + 1 >= argc || (flag != "--reps" && flag != "--pose" && flag != "--only")) {
      std::fprintf(stderr,
                   "render_measure: bad argument '%s' (usage: render_measure CONFIG "
                   "[--reps N] [--pose pose.json] [--only NAME])\n",
                   flag.c_str());
      return 2;
    }
    if (flag == "--reps") reps = std::max(1, std::atoi(argv[i + 1]));
    if (flag == "--pose") pose_file = argv[i + 1];
    if (flag == "--only") only = argv[i + 1];
  }
  const std::vector<std::string> names = {"lower_map", "upper_map", "frontal", "lateral"};
  if (!only.empty() && std::find(names.begin(), names.end(), only) == names.end()) {
    std::fprintf(stderr,
                 "render_measure: --only %s: not a picture (lower_map, upper_map, frontal or "
                 "lateral)\n",
                 only.c_str());
    return 2;
  }
  try {
    const CaseConfig config = LoadCaseConfig(argv[1]);
    CaseSession session(config);
    const Eigen::Isometry3d X_LU =
        pose_file.empty() ? session.ConfigStartPose() : ReadPoseFile(pose_file);
    ReportAnalysis analysis = AnalyzePose(session, X_LU);
    const JawPair& jaws = session.jaws();
    const render::MapScale scale{config.report.map_max_mm, config.contact_band_mm,
                                 config.report.map_penetration_from_mm};
    const int w = config.report.image_width_px;
    const std::vector<std::pair<const char*, std::function<render::Image()>>> pictures = {
        {"lower_map",
         [&] { return RenderContactMap(Arch::kLower, jaws, analysis, scale, w).image; }},
        {"upper_map",
         [&] { return RenderContactMap(Arch::kUpper, jaws, analysis, scale, w).image; }},
        {"frontal", [&] { return RenderSideView(SideView::kFrontal, jaws, analysis, scale, w); }},
        {"lateral",
         [&] { return RenderSideView(SideView::kLateralRight, jaws, analysis, scale, w); }}};
    double total = 0;
    for (const auto& [name, render] : pictures) {
      if (!only.empty() && only != name) continue;
      std::vector<double> cpu;
      std::string png;
      for (int r = 0; r < reps; ++r) {
        const double t0 = occlude::ThreadCpuSeconds();
        png = EncodePng(render());
        cpu.push_back(occlude::ThreadCpuSeconds() - t0);
      }
      std::sort(cpu.begin(), cpu.end());
      total += cpu[cpu.size() / 2];
      std::printf("%-10s %7.1f ms  png %8zu bytes  fnv %016llx\n", name, 1e3 * cpu[cpu.size() / 2],
                  png.size(), static_cast<unsigned long long>(Fnv1a(png)));
    }
    std::printf("%-10s %7.1f ms (sum of medians, thread CPU)\n", "all", 1e3 * total);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_measure: %s\n", e.what());
    return 1;
  }
  return 0;
}
