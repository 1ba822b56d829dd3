// The report of one pose as files (see report_writer.h).
#include "report/report_writer.h"

#include <functional>
#include <vector>

#include "base/output_files.h"
#include "base/tasks.h"
#include "base/timing.h"
#include "base/user_error.h"
#include "occlude/io/mesh_io.h"
#include "report/report_document.h"
#include "report/report_images.h"

namespace occlude::app {
namespace {

// The 3D view section of report.html: the view's poses, or the analysis's pose alone; its
// display meshes decimated here (or read from the cache) when the view brings none.
std::string ReportViewerHtml(const CaseSession& session, const ReportAnalysis& analysis,
                             const ReportView& view) {
  DisplayJaws own;
  if (view.display == nullptr) own = DecimateJawsForViewer(session.jaws(), session.cache().get());
  const DisplayJaws& display = view.display != nullptr ? *view.display : own;
  ViewerInputs in = ReportViewerInputs(session, display);
  in.proposals = view.poses;
  if (in.proposals.empty()) {
    in.proposals.push_back(
        ViewerProposalOf(display, analysis, "this pose", AnalysisNumbersJson(analysis)));
  }
  return ViewerSection(in);
}

io::VertexValues ColouredValues(const std::vector<float>& distance_mm, const ContactScale& scale) {
  io::VertexValues v;
  v.distance_mm = distance_mm;
  v.rgb.reserve(distance_mm.size());
  for (const float d : distance_mm) v.rgb.push_back(ContactColour(d, scale));
  return v;
}

}  // namespace

ReportFiles MakeReportFiles(CaseSession& session, ReportAnalysis& analysis,
                            const std::string& pose_source, const std::string& search_json,
                            const std::string& search_html, const ReportView& view) {
  const CaseConfig& config = session.config();
  const JawPair& jaws = session.jaws();
  const double t0 = NowSeconds();
  const render::MapScale scale{config.report.map_max_mm, config.contact_band_mm,
                               config.report.map_penetration_from_mm};
  const int w = config.report.image_width_px;
  std::string png[4];
  ReportInputs in;
  in.config = &config;
  in.jaws = &jaws;
  in.analysis = &analysis;
  in.pose_source = pose_source;
  in.search_json = search_json;
  in.search_html = search_html;
  double view_s = 0.0;
  {
    // Independent tasks on two threads, the slowest first (a side view rasterizes both whole
    // jaws, a map one jaw's occlusal side; the 3D view decimates both jaws when the caller
    // brings no display meshes, else only writes them out).
    RunTasks({
        [&] { png[2] = EncodePng(RenderSideView(SideView::kFrontal, jaws, analysis, scale, w)); },
        [&] {
          png[3] = EncodePng(RenderSideView(SideView::kLateralRight, jaws, analysis, scale, w));
        },
        [&] {
          const double t_view = NowSeconds();
          in.viewer_html = ReportViewerHtml(session, analysis, view);
          view_s = NowSeconds() - t_view;
        },
        [&] { png[0] = EncodePng(RenderContactMap(Arch::kLower, jaws, analysis, scale, w).image); },
        [&] { png[1] = EncodePng(RenderContactMap(Arch::kUpper, jaws, analysis, scale, w).image); },
    });
  }
  analysis.timings_s.emplace_back("render (pictures and 3D view, two threads)", NowSeconds() - t0);
  analysis.timings_s.emplace_back("3D view", view_s);
  in.pictures = {{"Lower arch, occlusal contact map", png[0], "lower_map.png"},
                 {"Upper arch, occlusal contact map", png[1], "upper_map.png"},
                 {"Frontal view", png[2], "frontal.png"},
                 {"Right lateral view", png[3], "lateral.png"}};
  ReportFiles out;
  for (const auto& p : in.pictures) out.files.emplace_back(p.file, p.png);
  out.files.emplace_back("metrics.json", MetricsJson(in));
  out.files.emplace_back("pose.json", PoseJson(in));
  out.files.emplace_back("report.html", ReportHtml(in));
  out.upper_at_pose = jaws.upper_U->Transformed(analysis.X_LU);
  out.lower_L = jaws.lower_L;
  const ContactScale colours{scale.max_mm, scale.band_mm, scale.penetration_from_mm};
  out.upper_values = ColouredValues(analysis.upper_vertex_mm, colours);
  out.lower_values = ColouredValues(analysis.lower_vertex_mm, colours);
  return out;
}

void WriteReportFiles(const std::filesystem::path& out, const ReportFiles& files,
                      const std::vector<std::pair<std::string, std::string>>& extra) {
  for (const auto& [name, content] : extra) WriteFileAtomic(out / name, content);
  for (const auto& [name, content] : files.files) {
    if (name == "report.html") continue;  // last: its presence means the report is complete
    WriteFileAtomic(out / name, content);
  }
  try {
    io::WriteBinaryStl(files.upper_at_pose, out / "upper_at_pose.stl",
                       "occlude upper jaw at the report pose (frame L, mm)");
    io::WriteColouredPly(files.upper_at_pose, files.upper_values, out / "upper_at_pose.ply");
    if (files.lower_L) io::WriteColouredPly(*files.lower_L, files.lower_values, out / "lower.ply");
  } catch (const io::MeshError& e) {
    throw UserError(e.what());
  }
  for (const auto& [name, content] : files.files) {
    if (name == "report.html") WriteFileAtomic(out / name, content);
  }
}

}  // namespace occlude::app
