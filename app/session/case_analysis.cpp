// The arch analysis of a case (case_analysis.h): AnalyzeArch on each jaw (both at once), the given
// landmarks applied per jaw, and ComputeRelationships at a pose.
#include "session/case_analysis.h"

#include <optional>

#include "base/tasks.h"
#include "base/user_error.h"
#include "occlude/io/landmark_file.h"
#include "session/analysis_entry.h"
#include "session/oracle_cache.h"

namespace occlude::app {

analysis::ArchAnalysis AnalyzeJaw(const io::TriangleMesh& mesh, io::Jaw jaw, OracleCache* cache) {
  const analysis::ArchAnalysisOptions options;
  return MadeOrCached(
      cache, kArchAnalysisEntryKind, [&] { return ArchAnalysisKey(mesh, jaw, options); },
      [&] { return analysis::AnalyzeArch(mesh, jaw, options); }, EncodeArchAnalysis,
      DecodeArchAnalysis);
}

CaseAnalysis AnalyzeCase(const JawPair& pair, const std::vector<io::Landmark>& given,
                         OracleCache* cache) {
  CaseAnalysis a;
  // The two jaws are analysed independently, at once.
  RunTasks({[&] { a.upper_U = AnalyzeJaw(*pair.upper_U, io::Jaw::kUpper, cache); },
            [&] { a.lower_L = AnalyzeJaw(*pair.lower_L, io::Jaw::kLower, cache); }});
  analysis::ApplyGivenLandmarks(given, &a.lower_L);
  analysis::ApplyGivenLandmarks(given, &a.upper_U);
  a.has_given_landmarks = !given.empty();
  return a;
}

analysis::Relationships RelationshipsAt(const CaseAnalysis& a, const Eigen::Isometry3d& X_LU) {
  // The lower arch frame is set whenever the arch curve was found (even when no tooth was).
  std::optional<analysis::ArchFrame> lower_frame_L;
  if (a.lower_L.ok() || !a.lower_L.arch_curve_J.empty()) lower_frame_L = a.lower_L.frame;
  return analysis::ComputeRelationships(a.upper_U.Points(), a.lower_L.Points(), X_LU,
                                        lower_frame_L);
}

std::vector<analysis::ArchLandmark> LandmarksInL(const CaseAnalysis& a,
                                                 const Eigen::Isometry3d& X_LU) {
  std::vector<analysis::ArchLandmark> out = a.lower_L.landmarks;
  for (analysis::ArchLandmark l : a.upper_U.landmarks) {
    l.landmark.p = X_LU * l.landmark.p;
    out.push_back(l);
  }
  return out;
}

analysis::ArchFrame ViewFrame(const CaseAnalysis& a, const analysis::Relationships& r,
                              const Eigen::Isometry3d& X_LU) {
  if (!r.frame_source.empty()) return r.frame_L;
  analysis::ArchFrame f;
  if (a.upper_U.arch_curve_J.empty()) return f;
  const analysis::ArchFrame& u = a.upper_U.frame;
  f.origin_J = X_LU * u.origin_J;
  f.lateral_J = X_LU.linear() * u.lateral_J;
  f.anterior_J = X_LU.linear() * u.anterior_J;
  f.occlusal_J = -(X_LU.linear() * u.occlusal_J);  // the upper's occlusal side faces down
  return f;
}

std::vector<io::Landmark> GivenAtReference(const Eigen::Isometry3d& X_LU_ref,
                                           std::vector<io::Landmark> given) {
  for (io::Landmark& l : given) {
    if (l.jaw == io::Jaw::kUpper) l.p = X_LU_ref * l.p;
  }
  return given;
}

std::vector<io::Landmark> ReadGivenLandmarks(const std::filesystem::path& file) {
  try {
    return io::ReadLandmarkFile(file);
  } catch (const io::LandmarkFileError& e) {
    throw UserError(e.what());
  }
}

}  // namespace occlude::app
