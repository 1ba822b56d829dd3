// AnalyzeArch (arch_analysis.h): geometry, teeth, landmarks, frame.
#include "arch_analysis.h"

namespace occlude::analysis {

const char* ToString(ToothSource source) {
  switch (source) {
    case ToothSource::kParts:
      return "parts";
    case ToothSource::kComponents:
      return "components";
    default:
      return "segmented";
  }
}

const char* ToString(LandmarkSource source) {
  return source == LandmarkSource::kGiven ? "given" : "detected";
}

}  // namespace occlude::analysis
