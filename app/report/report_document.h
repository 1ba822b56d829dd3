// The report's text outputs: metrics.json (contact and penetration totals, spots,
// per-tooth table, settings, timings), pose.json (X_LU readable by ReadPoseFile,
// plus translation/rotation about the pivot) and report.html (one self-contained
// page: pose, metrics, maps as embedded base64 PNG, per-tooth table, settings).
#pragma once

#include <string>
#include <vector>

#include "config/case_config.h"
#include "report/report_analysis.h"
#include "session/jaw_pair.h"
#include "viewer/html_text.h"  // Base64 of the embedded images

namespace occlude::app {

struct ReportInputs {
  const CaseConfig* config = nullptr;
  const JawPair* jaws = nullptr;
  const ReportAnalysis* analysis = nullptr;
  std::string pose_source;  ///< "start pose of the config" or the pose file
  /// (title, PNG bytes, file name) of each picture, in page order.
  struct Picture {
    std::string title, png, file;
  };
  std::vector<Picture> pictures;
  /// From propose/refine: a JSON object (text) stored under "search" in metrics.json, and an
  /// HTML fragment (the proposals, the points treated as scan artefacts) after the metrics.
  std::string search_json;
  std::string search_html;
  /// The 3D view section (report/report_viewer.h), placed before the still images.
  std::string viewer_html;
};

std::string MetricsJson(const ReportInputs& in);
std::string PoseJson(const ReportInputs& in);
std::string ReportHtml(const ReportInputs& in);

}  // namespace occlude::app
