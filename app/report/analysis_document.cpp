// The outputs of `occlude analyze` (analysis_document.h).
#include "report/analysis_document.h"

#include <nlohmann/json.hpp>

#include "base/json_values.h"
#include "report/relationships_json_internal.h"
#include "report/report_images.h"

namespace occlude::app {
namespace {

using nlohmann::json;

json TeethJson(const analysis::ArchAnalysis& a, const Eigen::Isometry3d& X_LJ) {
  json teeth = json::array();
  for (const analysis::ArchTooth& t : a.teeth) {
    teeth.push_back({{"fdi", t.fdi},
                     {"centre", Vec(X_LJ * t.centre_J)},
                     {"source", analysis::ToString(t.source)},
                     {"confidence", t.confidence}});
  }
  return teeth;
}

json JawJson(const analysis::ArchAnalysis& a) {
  return {{"error", a.ok() ? json(nullptr) : json(a.error)}, {"notes", a.notes}};
}

json LandmarksJson(const std::vector<analysis::ArchLandmark>& landmarks_L,
                   const std::vector<Eigen::Vector2d>& px) {
  json out = json::array();
  for (std::size_t i = 0; i < landmarks_L.size(); ++i) {
    const analysis::ArchLandmark& l = landmarks_L[i];
    out.push_back({{"jaw", io::ToString(l.landmark.jaw)},
                   {"tooth", l.landmark.tooth_fdi},
                   {"type", io::ToString(l.landmark.type)},
                   {"p_L", Vec(l.landmark.p)},
                   {"source", analysis::ToString(l.source)},
                   {"confidence", l.confidence},
                   {"method", l.method},
                   {"png_px", json::array({px[i].x(), px[i].y()})}});
  }
  return out;
}

}  // namespace

AnalysisFiles MakeAnalysisFiles(const AnalysisInputs& in) {
  const CaseAnalysis& a = *in.analysis;
  AnalysisFiles out;
  out.relationships = RelationshipsAt(a, in.X_LU);
  for (const analysis::ArchAnalysis* jaw : {&a.lower_L, &a.upper_U}) {
    if (!jaw->ok()) out.warnings.push_back(jaw->error);
  }
  const std::vector<analysis::ArchLandmark> landmarks_L = LandmarksInL(a, in.X_LU);
  const LandmarkImage image = RenderLandmarkMap(
      *in.jaws, in.X_LU, landmarks_L, ViewFrame(a, out.relationships, in.X_LU), in.image_width_px);
  json j = {
      {"case", in.case_name},
      {"pose_source", in.pose_source},
      {"X_LU", Matrix(in.X_LU.matrix())},
      {"landmarks_file", in.landmarks_source.empty() ? json(nullptr) : json(in.landmarks_source)},
      {"frame", RelationshipFrameJson(out.relationships)},
      {"teeth",
       {{"lower", TeethJson(a.lower_L, Eigen::Isometry3d::Identity())},
        {"upper", TeethJson(a.upper_U, in.X_LU)}}},
      {"landmarks", LandmarksJson(landmarks_L, image.px)},
      {"relationships", RelationshipsJson(out.relationships)},
      {"jaws", {{"lower", JawJson(a.lower_L)}, {"upper", JawJson(a.upper_U)}}},
      {"warnings", out.warnings}};
  if (j["frame"].is_null()) j["frame_reason"] = out.relationships.overjet.note;
  out.files = {{"analysis.json", j.dump(2) + "\n"}, {"landmarks.png", EncodePng(image.image)}};
  return out;
}

}  // namespace occlude::app
