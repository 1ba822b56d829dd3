// The report of one pose as files: the contact maps and views (rendered on two threads),
// metrics.json, pose.json, report.html and the upper jaw at the pose as STL. Everything is
// computed before the first file is written, and every file is written atomically, so a
// failed run leaves no half-written output. Used by report, propose and refine.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "report/report_analysis.h"
#include "session/case_session.h"

namespace occlude::app {

struct ReportFiles {
  std::vector<std::pair<std::string, std::string>> files;  ///< (file name, contents)
  io::TriangleMesh upper_at_pose;                          ///< written as upper_at_pose.stl
};

/// Renders the pictures and serializes the documents. `search_json` / `search_html`: see
/// ReportInputs (empty for a plain report).
ReportFiles MakeReportFiles(CaseSession& session, ReportAnalysis& analysis,
                            const std::string& pose_source, const std::string& search_json = "",
                            const std::string& search_html = "");

/// Writes the files (and `extra` ones first) into `out`, each atomically.
void WriteReportFiles(const std::filesystem::path& out, const ReportFiles& files,
                      const std::vector<std::pair<std::string, std::string>>& extra = {});

}  // namespace occlude::app
