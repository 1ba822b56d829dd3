// The texts the viewer page inlines, compiled in by CMake (app/viewer/CMakeLists.txt)
// from Debian's libjs-three (three.js r111, OrbitControls) and this folder's
// viewer.js and viewer.css, so a page needs no network and no files beside it.
#pragma once

namespace occlude::app::viewer_assets {

extern const char* const kThreeJs;          ///< three.min.js (defines the global THREE)
extern const char* const kOrbitControlsJs;  ///< examples/js/controls/OrbitControls.js
extern const char* const kViewerJs;         ///< the page script (viewer.js)
extern const char* const kViewerCss;        ///< the page style (viewer.css)

}  // namespace occlude::app::viewer_assets
