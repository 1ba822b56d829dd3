// A view of a surface along one axis: per square cell of a grid in the plane across the axis,
// the highest point of the surface along the axis (the envelope a camera far out on the axis
// sees) and the triangle it lies on. The arch analysis reads crowns, cusps and the arch curve
// off such maps.
//
// Frames: the view's axes are orthonormal vectors in the mesh's frame J; a point p_J has plane
// coordinates (e1 . (p - origin), e2 . (p - origin)) and height up . (p - origin), all mm.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::analysis {

struct ViewAxes {
  Eigen::Vector3d origin_J = Eigen::Vector3d::Zero();
  Eigen::Vector3d e1_J = Eigen::Vector3d::UnitX();
  Eigen::Vector3d e2_J = Eigen::Vector3d::UnitY();
  Eigen::Vector3d up_J = Eigen::Vector3d::UnitZ();

  Eigen::Vector2d Plane(const Eigen::Vector3d& p_J) const {
    const Eigen::Vector3d d = p_J - origin_J;
    return {e1_J.dot(d), e2_J.dot(d)};
  }
  double Height(const Eigen::Vector3d& p_J) const { return up_J.dot(p_J - origin_J); }
  Eigen::Vector3d Point(const Eigen::Vector2d& q, double h) const {
    return origin_J + q.x() * e1_J + q.y() * e2_J + h * up_J;
  }
};

/// Axes with `up` and any two unit vectors completing it (deterministic).
ViewAxes AxesAround(const Eigen::Vector3d& origin_J, const Eigen::Vector3d& up_J);

struct HeightMap {
  ViewAxes axes;
  double cell = 0.2;                   ///< mm
  int nx = 0, ny = 0;                  ///< cells along e1, e2
  Eigen::Vector2d corner{0.0, 0.0};    ///< plane coordinates of cell (0, 0)'s lower corner
  std::vector<double> height;          ///< per cell, NaN where the surface does not cover it
  std::vector<std::int32_t> triangle;  ///< per cell, the triangle seen there, -1 if none

  int Index(int i, int j) const { return j * nx + i; }
  bool Filled(int c) const { return !std::isnan(height[static_cast<std::size_t>(c)]); }
  Eigen::Vector2d Centre(int c) const {
    return corner + cell * Eigen::Vector2d(c % nx + 0.5, c / nx + 0.5);
  }
  /// The cell containing plane point q, or -1 outside the grid.
  int CellAt(const Eigen::Vector2d& q) const;
  /// The seen surface point of a filled cell, in J.
  Eigen::Vector3d Point_J(int c) const {
    return axes.Point(Centre(c), height[static_cast<std::size_t>(c)]);
  }
};

/// Per cell, the highest filled cell within the square of half-side `radius_mm` around it (NaN
/// where none is filled): a separable running maximum.
std::vector<double> MaxFilter(const HeightMap& map, double radius_mm);

/// Per cell of a view whose plane (height 0) is the occlusal plane, how much it is crown: 0 for
/// empty cells, cells below `floor` and cells more than `below_top_mm` below the highest cell
/// within `radius_mm` (the gingiva beside a crown is lower than the crown); else the square of
/// its height above that limit (cusps and edges weigh most), in mm^2.
std::vector<double> CrownWeights(const HeightMap& map, double floor, double below_top_mm,
                                 double radius_mm);

/// Rasterizes the triangles `triangles` of `mesh` (all when empty) seen from far out along
/// `axes.up_J`, on cells of `cell` mm (> 0) covering their footprint plus one cell.
HeightMap RasterizeTop(const io::TriangleMesh& mesh, const std::vector<std::int32_t>& triangles,
                       const ViewAxes& axes, double cell);

}  // namespace occlude::analysis
