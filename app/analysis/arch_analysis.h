// The arch analysis of one jaw from its mesh alone (no bite, any frame): the occlusal plane and
// an arch frame, the arch curve, the dental midline, the teeth with their FDI numbers and the
// landmarks of ../shared/docs/clinical.md on each tooth found, each with a confidence and the
// method that found it. What cannot be found is left out (and said in `notes`), never guessed.
//
// Frames: J is the frame the mesh came in (mm). The arch frame lives in J: `occlusal_J` points
// out of this jaw's crowns towards where the opposing jaw would be (for a lower jaw up, for an
// upper jaw down, anatomically), `anterior_J` towards the incisors in the occlusal plane, and
// `lateral_J` to the patient's left for either jaw. Seen anatomically (clinical.md: x left,
// y anterior, z lower -> upper) the lower jaw's frame is (x, y, z) and the upper's (x, y, -z).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "occlude/io/dental.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::analysis {

/// The arch frame of one jaw, in the mesh's frame J (unit vectors, mm for the origin).
struct ArchFrame {
  Eigen::Vector3d origin_J = Eigen::Vector3d::Zero();     ///< on the dental midline, in the plane
  Eigen::Vector3d lateral_J = Eigen::Vector3d::UnitX();   ///< to the patient's left
  Eigen::Vector3d anterior_J = Eigen::Vector3d::UnitY();  ///< towards the incisors
  Eigen::Vector3d occlusal_J = Eigen::Vector3d::UnitZ();  ///< plane normal, out of the crowns
};

/// How a tooth was found.
enum class ToothSource {
  kParts,       ///< "parts": a mesh part carrying its tooth number
  kComponents,  ///< "components": a separate shell of the mesh, numbered along the arch
  kSegmented,   ///< "segmented": cut out of a single surface along the arch curve
};
const char* ToString(ToothSource source);

/// Where a landmark came from.
enum class LandmarkSource { kDetected, kGiven };
/// "detected" or "given".
const char* ToString(LandmarkSource source);

struct ArchTooth {
  int fdi = 0;
  Eigen::Vector3d centre_J = Eigen::Vector3d::Zero();  ///< area centroid of its crown surface
  ToothSource source = ToothSource::kSegmented;
  double mesial_mm = 0.0;  ///< extent along the arch curve (arc length, right to left), mm
  double distal_mm = 0.0;
  double confidence = 0.0;  ///< in [0, 1]
};

struct ArchLandmark {
  io::Landmark landmark;  ///< jaw, tooth, type and the point p in J
  LandmarkSource source = LandmarkSource::kDetected;
  double confidence = 0.0;  ///< in [0, 1]; 1 for given landmarks
  std::string method;       ///< how it was found ("given" for given ones)
};

struct ArchAnalysis {
  io::Jaw jaw = io::Jaw::kLower;
  /// Empty on success; else why the jaw could not be analysed (e.g. no tooth found). The frame
  /// and curve may still be filled when only the teeth failed.
  std::string error;
  bool ok() const { return error.empty(); }

  ArchFrame frame;
  /// Arch curve in J, patient's right to left, about `ArchAnalysisOptions::curve_step_mm` apart:
  /// the middle of the crowns across the arch, at the height of their occlusal surface (cusp
  /// tips and incisal edges). Arc length along it is the `mesial_mm`/`distal_mm` of the teeth.
  std::vector<Eigen::Vector3d> arch_curve_J;
  /// The dental midline: the point between the central incisors (their mesial contacts when
  /// found) in J; the midline is the line through it along `frame.anterior_J`.
  Eigen::Vector3d midline_J = Eigen::Vector3d::Zero();
  /// Teeth in arch order, patient's right to left.
  std::vector<ArchTooth> teeth;
  std::vector<ArchLandmark> landmarks;
  /// What was left out or is doubtful, one line each.
  std::vector<std::string> notes;

  /// The landmark of a tooth and type, or nullptr.
  const ArchLandmark* Find(int fdi, io::LandmarkType type) const;
  /// Every landmark's point (io::Landmark, in J).
  std::vector<io::Landmark> Points() const;
};

struct ArchAnalysisOptions {
  /// Cell of the occlusal height maps, mm (> 0): the resolution of every detection.
  double grid_mm = 0.2;
  /// Spacing of the arch curve's points, mm (> 0).
  double curve_step_mm = 0.25;
  /// Crowns are the surface at most this far below the occlusal plane (along occlusal_J), mm.
  double crown_depth_mm = 5.0;
};

/// Analyses one jaw (`which`) of `jaw_J`, a mesh in any frame J. Teeth come from mesh parts
/// with tooth numbers when there are any, else from separate shells, else from segmenting the
/// surface along the arch. A mesh on which no tooth can be found gives a result whose `error`
/// says so (not an exception). Throws std::invalid_argument naming the option for options out
/// of range. Deterministic, single-threaded.
ArchAnalysis AnalyzeArch(const io::TriangleMesh& jaw_J, io::Jaw which,
                         const ArchAnalysisOptions& options = {});

/// 16 hex digits that change whenever the analysis's code does (a hash of its sources, made by
/// the build): what a cached AnalyzeArch result is keyed by besides the mesh and the options.
const char* ArchAnalysisCodeVersion();

/// Given landmarks override detected ones: each of `given` of this analysis's jaw replaces the
/// detected landmark of the same tooth and type (or is added), with source kGiven, confidence 1
/// and method "given". Points are in the analysis's frame J. Landmarks of the other jaw are
/// ignored.
void ApplyGivenLandmarks(const std::vector<io::Landmark>& given, ArchAnalysis* analysis);

}  // namespace occlude::analysis
