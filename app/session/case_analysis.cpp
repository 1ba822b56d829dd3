// The arch analysis of a case (case_analysis.h): AnalyzeArch on each jaw, the given landmarks
// applied per jaw, and ComputeRelationships at a pose.
#include "session/case_analysis.h"

#include <optional>

#include "base/user_error.h"
#include "occlude/io/landmark_file.h"

namespace occlude::app {

CaseAnalysis AnalyzeCase(const JawPair& pair, const std::vector<io::Landmark>& given) {
  CaseAnalysis a;
  a.lower_L = analysis::AnalyzeArch(*pair.lower_L, io::Jaw::kLower);
  a.upper_U = analysis::AnalyzeArch(*pair.upper_U, io::Jaw::kUpper);
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
