// The report of one pose as files: the contact maps and views (rendered on two threads),
// metrics.json, pose.json, report.html (with the 3D view, report_viewer.h), the upper jaw at
// the pose as STL, and both jaws as coloured PLY (upper_at_pose.ply, lower.ply: per-vertex
// contact colour and distance_mm, io/coloured_ply.h). Everything is
// computed before the first file is written, and every file is written atomically, so a
// failed run leaves no half-written output. Used by report, propose and refine.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "occlude/io/coloured_ply.h"
#include "report/report_analysis.h"
#include "report/report_viewer.h"
#include "session/case_session.h"

namespace occlude::app {

struct ReportFiles {
  std::vector<std::pair<std::string, std::string>> files;  ///< (file name, contents)
  io::TriangleMesh upper_at_pose;                          ///< written as upper_at_pose.stl
  std::shared_ptr<const io::TriangleMesh> lower_L;         ///< written as lower.ply
  /// Per vertex of upper_at_pose / lower_L: contact colour and signed distance to the other
  /// jaw (mm; kContactFarValue beyond the report's reach), for the PLY files.
  io::VertexValues upper_values, lower_values;
};

/// The 3D view of report.html: the display meshes and the poses to switch between.
struct ReportView {
  const DisplayJaws* display = nullptr;  ///< nullptr: decimated from the session's jaws
  std::vector<ViewerProposal> poses;     ///< empty: the analysis's pose alone
};

/// Renders the pictures and serializes the documents. `search_json` / `search_html`: see
/// ReportInputs (empty for a plain report).
ReportFiles MakeReportFiles(CaseSession& session, ReportAnalysis& analysis,
                            const std::string& pose_source, const std::string& search_json = "",
                            const std::string& search_html = "", const ReportView& view = {});

/// Writes the files (and `extra` ones first) into `out`, each atomically.
void WriteReportFiles(const std::filesystem::path& out, const ReportFiles& files,
                      const std::vector<std::pair<std::string, std::string>>& extra = {});

}  // namespace occlude::app
