// The report's pictures: occlusal contact maps of each arch (seen along the
// occlusal axis, coloured by signed distance to the opposing arch, with contact
// spots, tooth numbers, mm legend, scale bar and orientation), and frontal and
// lateral views of both jaws at the pose. PNG encoding. OpenCV stays inside the
// .cpp (drawing text and shapes, PNG).
#pragma once

#include <string>
#include <vector>

#include "analysis/arch_analysis.h"
#include "report/render_raster.h"
#include "report/report_analysis.h"
#include "report/report_colours.h"
#include "session/jaw_pair.h"

namespace occlude::app {

enum class Arch { kLower, kUpper };
enum class SideView { kFrontal, kLateralRight };

struct MapImage {
  render::Image image;
  render::OrthoView view;  ///< maps points in L to pixels of `image` (offset included)
  int map_x = 0, map_y = 0, map_width = 0, map_height = 0;  ///< the map's area (legend excluded)
};

/// Occlusal contact map of one arch at analysis.X_LU. `width_px` is the image width.
MapImage RenderContactMap(Arch arch, const JawPair& jaws, const ReportAnalysis& analysis,
                          const render::MapScale& scale, int width_px);

/// Both jaws at the pose from the front or the patient's right, shaded, near-contact
/// surfaces in the map colours.
render::Image RenderSideView(SideView side, const JawPair& jaws, const ReportAnalysis& analysis,
                             const render::MapScale& scale, int width_px);

/// Marker colours of landmarks.png: detected landmarks are filled circles, given ones filled
/// squares, each with a dark outline.
inline constexpr render::Rgb kDetectedLandmarkColour = {0, 102, 204};
inline constexpr render::Rgb kGivenLandmarkColour = {230, 110, 0};

struct LandmarkImage {
  render::Image image;
  std::vector<Eigen::Vector2d> px;  ///< per landmark, where its marker is centred
};

/// landmarks.png: both arches from the occlusal side, stacked (the lower from above, the upper
/// at X_LU from below; `frame_L` orients them, anterior up, the patient's sides marked), each of
/// `landmarks_L` (points in L at the pose) drawn as a marker labelled with its tooth and type,
/// and a legend of the markers and type abbreviations. `width_px` is the image width.
LandmarkImage RenderLandmarkMap(const JawPair& jaws, const Eigen::Isometry3d& X_LU,
                                const std::vector<analysis::ArchLandmark>& landmarks_L,
                                const analysis::ArchFrame& frame_L, int width_px);

/// PNG file contents of an image. Throws std::runtime_error if encoding fails.
std::string EncodePng(const render::Image& image);

}  // namespace occlude::app
