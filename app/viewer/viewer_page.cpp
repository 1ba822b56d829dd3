// The viewer's HTML (see viewer_page.h): the elements viewer.js fills, the data
// object, and the inlined three.js, OrbitControls, script and style.
#include "viewer/viewer_page.h"

#include "viewer/html_text.h"
#include "viewer/viewer_assets.h"
#include "viewer/viewer_data_internal.h"

namespace occlude::app {
namespace {

// Counts what window.onerror catches (before any other script runs), for tests and tools.
constexpr const char* kErrorCounter =
    "window.occludeViewerStart=performance.now();window.occludeViewerErrors=[];"
    "window.addEventListener('error',function(e){occludeViewerErrors.push(String(e.message)+"
    "' at '+e.lineno+':'+e.colno);document.body.dataset.viewerErrors=String("
    "occludeViewerErrors.length);});"
    "window.addEventListener('unhandledrejection',function(e){occludeViewerErrors.push("
    "'unhandled rejection: '+String(e.reason));document.body.dataset.viewerErrors=String("
    "occludeViewerErrors.length);});"
    "document.body.dataset.viewerErrors='0';";

// The controls and panels viewer.js fills in.
constexpr const char* kMarkup = R"html(<div class="ov-main"><div class="ov-stage">
<div class="ov-toolbar">View:
<button type="button" data-view="oblique">oblique</button>
<button type="button" data-view="occlusal-lower">occlusal (lower)</button>
<button type="button" data-view="occlusal-upper">occlusal (upper)</button>
<button type="button" data-view="frontal">frontal</button>
<button type="button" data-view="right">right</button>
<button type="button" data-view="left">left</button>
<label>upper jaw <select id="occlude-viewer-upper"><option value="solid">solid</option>
<option value="transparent">transparent</option><option value="hidden">hidden</option></select></label>
<label><input type="checkbox" id="occlude-viewer-lower" checked> lower jaw</label></div>
<canvas id="occlude-viewer-canvas"></canvas>
<p class="ov-note" id="occlude-viewer-status">The 3D view needs WebGL and JavaScript; the
still images of this report show the same contact map.</p></div>
<div class="ov-side"><div class="ov-proposals" id="occlude-viewer-proposals"></div>
<table id="occlude-viewer-numbers"></table>
<div class="ov-ramp" id="occlude-viewer-ramp"></div>
<div class="ov-note" id="occlude-viewer-ramp-labels"></div>
<div class="ov-note"><span class="ov-swatch" id="occlude-viewer-pen-swatch"></span><span
id="occlude-viewer-pen-label"></span></div>
<div class="ov-note"><span class="ov-swatch" id="occlude-viewer-far-swatch"></span><span
id="occlude-viewer-far-label"></span></div>
<p class="ov-pick" id="occlude-viewer-pick">Click a surface to read the distance there.</p>
</div></div>
)html";

}  // namespace

std::string ViewerSection(const ViewerInputs& inputs) {
  const std::string data = ScriptSafeJson(viewer_detail::ViewerDataJson(inputs));
  std::string out;
  out.reserve(data.size() + 1200000);
  out += "<section class=\"occlude-viewer\" id=\"occlude-viewer\">\n<style>";
  out += viewer_assets::kViewerCss;
  out += "</style>\n<h2>" + HtmlEscape(inputs.title) + "</h2>\n";
  out += kMarkup;
  out += "<script type=\"application/json\" id=\"occlude-viewer-data\">" + data + "</script>\n";
  out += std::string("<script>") + kErrorCounter + "</script>\n<script>";
  out += viewer_assets::kThreeJs;
  out += "</script>\n<script>";
  out += viewer_assets::kOrbitControlsJs;
  out += "</script>\n<script>";
  out += viewer_assets::kViewerJs;
  out += "</script>\n</section>\n";
  return out;
}

std::string ViewerPage(const ViewerInputs& inputs) {
  const std::string section = ViewerSection(inputs);
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" +
         HtmlEscape(inputs.title) + "</title></head>\n<body style=\"margin:12px 18px\">\n" +
         section + "</body></html>\n";
}

std::string ViewerProposalEvent(const ViewerInputs& inputs, const ViewerProposal& proposal) {
  return viewer_detail::ProposalJson(inputs, proposal);
}

}  // namespace occlude::app
