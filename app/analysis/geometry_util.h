// Small geometric helpers of the arch analysis: principal axes of a surface, least-squares
// planes and quantiles of samples.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::analysis {

struct PrincipalAxes {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< unit columns, smallest spread first
  Eigen::Vector3d spread = Eigen::Vector3d::Zero();    ///< variances along them, mm^2
};

/// Area-weighted principal axes of the triangles `triangles` of `mesh` (all when empty).
PrincipalAxes SurfacePrincipalAxes(const io::TriangleMesh& mesh,
                                   const std::vector<std::int32_t>& triangles);

struct Plane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit
};

/// Least-squares plane through `points` (at least one; fewer than three give the normal +z).
Plane FitPlane(const std::vector<Eigen::Vector3d>& points);

/// The q-quantile (q in [0, 1]) of `values` with linear interpolation between order statistics;
/// 0 for an empty sample.
double Quantile(std::vector<double> values, double q);

}  // namespace occlude::analysis
