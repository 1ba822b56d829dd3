// Principal axes, planes and quantiles (geometry_util.h).
#include "geometry_util.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace occlude::analysis {

PrincipalAxes SurfacePrincipalAxes(const io::TriangleMesh& mesh,
                                   const std::vector<std::int32_t>& triangles) {
  const std::size_t n = triangles.empty() ? mesh.num_triangles() : triangles.size();
  double area = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < n; ++k) {
    const auto t = triangles.empty() ? k : static_cast<std::size_t>(triangles[k]);
    const Eigen::Vector3d &a = mesh.corner(t, 0), &b = mesh.corner(t, 1), &c = mesh.corner(t, 2);
    const double w = 0.5 * (b - a).cross(c - a).norm();
    const Eigen::Vector3d g = (a + b + c) / 3.0;
    area += w;
    sum += w * g;
    second += w * g * g.transpose();
  }
  PrincipalAxes out;
  if (area <= 0.0) return out;
  out.centre = sum / area;
  const Eigen::Matrix3d cov = second / area - out.centre * out.centre.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  out.axes = eig.eigenvectors();
  out.spread = eig.eigenvalues();
  return out;
}

Plane FitPlane(const std::vector<Eigen::Vector3d>& points) {
  Plane plane;
  if (points.empty()) return plane;
  for (const auto& p : points) plane.point += p;
  plane.point /= static_cast<double>(points.size());
  if (points.size() < 3) return plane;
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - plane.point) * (p - plane.point).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  plane.normal = eig.eigenvectors().col(0).normalized();
  return plane;
}

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const double pos = std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(lo), values.end());
  const double a = values[lo];
  if (lo + 1 >= values.size()) return a;
  const double b =
      *std::min_element(values.begin() + static_cast<std::ptrdiff_t>(lo) + 1, values.end());
  return a + (pos - static_cast<double>(lo)) * (b - a);
}

}  // namespace occlude::analysis
