// render_measure CONFIG [--reps N] [--pose pose.json] [--only NAME]: the report's four pictures of
// a case at a pose (default: the config's start pose), each rendered and PNG-encoded N times on one
// thread; prints per picture the median thread CPU time and a checksum of its PNG (a change of the
// rasterizer that keeps the checksums keeps the pictures byte for byte).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "base/timing.h"
#include "config/case_config.h"
#include "config/pose_file.h"
#include "occlude/io/content_hash.h"
#include "report/report_analysis.h"
#include "report/report_images.h"
#include "session/case_session.h"

namespace {

// The pictures, in the order they are measured.
const char* const kPictures[] = {"lower_map", "upper_map", "frontal", "lateral"};

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
  if (!only.empty() &&
      std::find(std::begin(kPictures), std::end(kPictures), only) == std::end(kPictures)) {
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
    const std::function<render::Image()> render[] = {
        [&] { return RenderContactMap(Arch::kLower, jaws, analysis, scale, w).image; },
        [&] { return RenderContactMap(Arch::kUpper, jaws, analysis, scale, w).image; },
        [&] { return RenderSideView(SideView::kFrontal, jaws, analysis, scale, w); },
        [&] { return RenderSideView(SideView::kLateralRight, jaws, analysis, scale, w); }};
    double total = 0;
    for (std::size_t k = 0; k < std::size(kPictures); ++k) {
      const std::string name = kPictures[k];
      if (!only.empty() && only != name) continue;
      std::vector<double> cpu;
      std::string png;
      for (int r = 0; r < reps; ++r) {
        const double t0 = occlude::ThreadCpuSeconds();
        png = EncodePng(render[k]());
        cpu.push_back(occlude::ThreadCpuSeconds() - t0);
      }
      std::sort(cpu.begin(), cpu.end());
      total += cpu[cpu.size() / 2];
      std::printf("%-10s %7.1f ms  png %8zu bytes  hash %s\n", name.c_str(),
                  1e3 * cpu[cpu.size() / 2], png.size(),
                  occlude::io::HashHex(occlude::io::Hash64(png.data(), png.size())).c_str());
    }
    std::printf("%-10s %7.1f ms (sum of medians, thread CPU)\n", "all", 1e3 * total);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_measure: %s\n", e.what());
    return 1;
  }
  return 0;
}
