// Private to occlude::viewer: the page's data as one JSON object, with the meshes,
// distances and colours as base64 of little-endian typed arrays (positions
// quantized to 16 bits over each mesh's bounds, distances to whole micrometres).
//
// Layout (what viewer.js reads):
//   {"title", "axes": {occlusal, anterior, lateral},
//    "scale": {max_mm, band_mm, penetration_from_mm, ramp: [[mm, "#rrggbb"]...],
//              penetration, far},
//    "jaws": [lower, upper], each {name, frame, vertices, triangles,
//              positions: {origin[3], step[3], data: uint16 x 3V},
//              index: {type: "uint16"|"uint32", data: 3T},
//              part: {type: "uint8"|"uint16", data: T}, parts: [{name, universal, fdi}]},
//    "proposals": [{label, X_LU: 16 numbers column-major, numbers: {...},
//                   lower: {distance_um: int16 V, colour: uint8 3V}, upper: {...}}],
//    "live": null | the path of the event stream of `proposal` events (one proposal each)}
// distance_um saturates at +-32766; 32767 = farther than 32.766 mm or out of reach.
#pragma once

#include <cstdint>
#include <string>

#include "viewer/viewer_page.h"

namespace occlude::app::viewer_detail {

/// Saturating and "far" codes of distance_um.
inline constexpr std::int16_t kDistanceFarCode = 32767;
inline constexpr std::int16_t kDistanceMaxCode = 32766;

/// Checks `inputs` (throws std::invalid_argument naming the field) and returns the
/// data object's JSON text (not yet made script-safe).
std::string ViewerDataJson(const ViewerInputs& inputs);

/// One proposal's JSON text in the layout of "proposals" (checked like ViewerDataJson).
std::string ProposalJson(const ViewerInputs& inputs, const ViewerProposal& proposal);

/// The distance code of d mm (see above).
std::int16_t DistanceCode(float d_mm);

}  // namespace occlude::app::viewer_detail
