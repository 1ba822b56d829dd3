// The outputs of `occlude analyze`: analysis.json (the frame, the teeth of each jaw, every
// landmark in L at the pose with its source and confidence, the clinical relationships) and
// landmarks.png (report_images.h: RenderLandmarkMap), computed together before anything is
// written.
//
// analysis.json: case, pose_source, X_LU (4x4), landmarks_file (or null); frame {origin_L,
// lateral, anterior, occlusal, source} (the relationships' frame in L; null with frame_reason
// when there is none); teeth {lower, upper: [{fdi, centre (mm, L at the pose), source (parts,
// components, segmented), confidence}]}; landmarks [{jaw, tooth, type, p_L (mm, L at the
// pose), source (detected or given), confidence, method, png_px [x, y] (the marker's centre in
// landmarks.png)}]; relationships (relationships_json_internal.h); jaws {lower, upper: {error
// (null when the jaw was analysed), notes [...]}}; warnings [...].
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <utility>
#include <vector>

#include "analysis/relationships.h"
#include "session/case_analysis.h"
#include "session/jaw_pair.h"

namespace occlude::app {

struct AnalysisInputs {
  std::string case_name;
  std::string pose_source;        ///< e.g. "the registered bite", "pose file <path>"
  std::string landmarks_source;   ///< the given landmarks' file, "" when none
  const JawPair* jaws = nullptr;  ///< lower in L, upper in U: the frames of `analysis`
  const CaseAnalysis* analysis = nullptr;
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
  int image_width_px = 1000;  ///< of landmarks.png
};

struct AnalysisFiles {
  std::vector<std::pair<std::string, std::string>> files;  ///< analysis.json, landmarks.png
  analysis::Relationships relationships;                   ///< at X_LU
  std::vector<std::string> warnings;  ///< one line per jaw on which no tooth was found
};

AnalysisFiles MakeAnalysisFiles(const AnalysisInputs& in);

}  // namespace occlude::app
