// The interactive 3D view: a self-contained HTML section (or whole page) that
// shows both jaws at a pose in WebGL (three.js, inlined), coloured by the
// contact map with its mm legend and penetration in its colour; orbit, zoom and
// pan; the upper jaw togglable and transparent; a click on a surface reads the
// distance there and the tooth; buttons for the standard views (occlusal,
// frontal, lateral); and a switcher between proposals (pose, numbers, colours).
// It opens offline: no resource is fetched at view time.
//
// Frames and units: the lower display mesh in L, the upper in U, each proposal's
// X_LU places U in L; mm everywhere. Distances are per display vertex (carry
// them over from the full meshes with DecimationResult::source_vertex).
//
// The page exposes its state for tests and tools: document.body.dataset has
// viewerReady ("1" once the first frame is drawn), viewerProposal (current
// index), viewerErrors (errors caught by window.onerror) and viewerFirstDrawMs;
// window.occludeViewer has setProposal(i), setView(name), setUpperMode(mode),
// drawnPixels() (reads the canvas back: {drawn, total, checksum}), pickAt(x, y)
// (canvas pixels from the top left: what a click there reads) and state().
// One viewer per page (its element ids are fixed).
//
// Live pages (ViewerInputs::live_events_path, served by serve/live_server.h): the page
// listens on that same-origin event stream for `proposal` events whose data is
// ViewerProposalEvent(); a proposal with a label already listed replaces it, another
// is added; either is shown at once. It sets dataset.viewerLive ("open" while the
// stream is connected, "closed" after), viewerUpdates (proposals received) and
// viewerUpdatedAt (Date.now() in ms when the new proposal's frame was drawn).
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "occlude/io/triangle_mesh.h"
#include "viewer/contact_colours.h"

namespace occlude::app {

/// One pose to show, with what the page lists beside it.
struct ViewerProposal {
  std::string label;  ///< e.g. "proposal 1"
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
  /// A small JSON object of the numbers to list, in its key order, e.g.
  /// {"contact area (mm²)": 13.2, "max penetration (mm)": 0.04, "status": "converged"}.
  std::string numbers_json = "{}";
  /// Per lower display vertex: signed distance to the upper at X_LU, mm (negative =
  /// penetration; kContactFarValue = no opposing surface within reach).
  std::vector<float> lower_distance_mm;
  std::vector<float> upper_distance_mm;  ///< per upper display vertex, to the lower
};

/// Directions in L for the standard views (e.g. copied from collision::ArchFrame).
struct ViewerAxes {
  Eigen::Vector3d occlusal_L = Eigen::Vector3d::UnitY();  ///< lower -> upper
  Eigen::Vector3d anterior_L = Eigen::Vector3d::UnitZ();  ///< towards the incisors
  Eigen::Vector3d lateral_L = Eigen::Vector3d::UnitX();   ///< patient's left
};

struct ViewerInputs {
  const io::TriangleMesh* lower_L = nullptr;  ///< display mesh (parts carry tooth numbers)
  const io::TriangleMesh* upper_U = nullptr;
  ViewerAxes axes;
  ContactScale scale;
  std::vector<ViewerProposal> proposals;  ///< at least one; the first is shown first
  std::string title = "Jaws at the pose";
  /// Empty: a still page. Else the path of the event stream to listen on, e.g. "/events".
  std::string live_events_path;
};

/// A <section> holding the style, the data and the scripts (three.js included), to
/// place in a page's body. Throws std::invalid_argument naming the field (a missing
/// mesh, no proposal, a distance count that is not the vertex count, numbers that are
/// not a JSON object, non-finite poses or distances).
std::string ViewerSection(const ViewerInputs& inputs);

/// A whole HTML document around ViewerSection. Same errors.
std::string ViewerPage(const ViewerInputs& inputs);

/// The data of a `proposal` event for a live page made from `inputs` (its display
/// meshes and scale): `proposal` as one line of JSON. Same errors as ViewerSection
/// for the meshes, the scale and the proposal's fields (named "proposal.<field>").
std::string ViewerProposalEvent(const ViewerInputs& inputs, const ViewerProposal& proposal);

}  // namespace occlude::app
