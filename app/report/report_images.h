// The report's pictures: occlusal contact maps of each arch (seen along the
// occlusal axis, coloured by signed distance to the opposing arch, with contact
// spots, tooth numbers, mm legend, scale bar and orientation), and frontal and
// lateral views of both jaws at the pose. PNG encoding. OpenCV stays inside the
// .cpp (drawing text and shapes, PNG).
#pragma once

#include <string>

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

/// PNG file contents of an image. Throws std::runtime_error if encoding fails.
std::string EncodePng(const render::Image& image);

}  // namespace occlude::app
