// The tooth view of an analytic crown surface for the landmark tests: tooth coordinates are the
// map's plane coordinates (u mesial, v buccal or labial, w along the occlusal axis), each cell's
// height the surface at the cell's centre, the span |u| <= half_length, |v| <= half_width, seen
// as a segmented scan's view (cut out of the jaw at u = +-half_length, not a whole crown).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>

#include "analysis/tooth_view.h"

namespace occlude::analysis::test {

inline ToothView SurfaceView(int fdi, io::Jaw jaw, double half_length_mm, double half_width_mm,
                             double cell_mm, const std::function<double(double, double)>& surface) {
  ToothView view;
  view.fdi = fdi;
  view.jaw = jaw;
  view.u_mesial = half_length_mm;
  view.u_distal = -half_length_mm;
  view.whole_crown = false;
  HeightMap& map = view.top;
  map.cell = cell_mm;
  map.corner = {-half_length_mm, -half_width_mm};
  map.nx = static_cast<int>(std::lround(2.0 * half_length_mm / map.cell));
  map.ny = static_cast<int>(std::lround(2.0 * half_width_mm / map.cell));
  map.height.assign(static_cast<std::size_t>(map.nx * map.ny), 0.0);
  map.triangle.assign(map.height.size(), -1);
  view.top_uvw.assign(map.height.size(), Eigen::Vector3d::Zero());
  for (int c = 0; c < map.nx * map.ny; ++c) {
    const Eigen::Vector2d q = map.Centre(c);
    map.height[static_cast<std::size_t>(c)] = surface(q.x(), q.y());
    view.top_uvw[static_cast<std::size_t>(c)] << q, map.height[static_cast<std::size_t>(c)];
  }
  return view;
}

}  // namespace occlude::analysis::test
