// Exact triangle / axis-aligned box overlap (separating-axis theorem), the test
// that decides which voxels are Surface voxels.
//
// Both the triangle and the box are closed sets: a triangle that only touches a
// box face, edge or corner overlaps it. Degenerate triangles (segments, points)
// are handled: an axis that degenerates to the zero vector can never separate
// and is skipped implicitly, and the remaining axes still decide exactly.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace occlude::collision {

/// A triangle prepared for many box tests: the triangle's projected interval on
/// each of the 13 candidate axes is computed once, so a box test only projects
/// the box centre. Overlaps() gives bit-for-bit the same answer as
/// TriangleBoxOverlap() for the same inputs (the same code computes both).
class TriangleBoxTester {
 public:
  TriangleBoxTester(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

  /// True when the closed triangle and the closed box {x : |x - center| <= half_size}
  /// (component-wise, half_size >= 0) share at least one point, up to double rounding
  /// (of the order of 1e-16 x the coordinates' magnitude).
  bool Overlaps(const Eigen::Vector3d& box_center, const Eigen::Vector3d& box_half_size) const {
    const Eigen::Vector3d& c = box_center;
    const Eigen::Vector3d& h = box_half_size;
    // Box face normals: the triangle's bounding box against the box.
    for (int i = 0; i < 3; ++i) {
      if (Separated(lo_[0][i], hi_[0][i], c[i], h[i])) return false;
    }
    // Triangle normal (zero for a degenerate triangle: then it never separates).
    const double rn =
        h.x() * std::abs(n_.x()) + h.y() * std::abs(n_.y()) + h.z() * std::abs(n_.z());
    if (Separated(lo_[1][0], hi_[1][0], n_.dot(c), rn)) return false;
    // Edge e crossed with the box axes x, y, z: (0, -e.z, e.y), (e.z, 0, -e.x),
    // (-e.y, e.x, 0). A zero axis projects everything to 0 and never separates.
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d& e = e_[j];
      const double ax = std::abs(e.x()), ay = std::abs(e.y()), az = std::abs(e.z());
      if (Separated(lo_[2 + j][0], hi_[2 + j][0], e.y() * c.z() - e.z() * c.y(),
                    h.y() * az + h.z() * ay) ||
          Separated(lo_[2 + j][1], hi_[2 + j][1], e.z() * c.x() - e.x() * c.z(),
                    h.x() * az + h.z() * ax) ||
          Separated(lo_[2 + j][2], hi_[2 + j][2], e.x() * c.y() - e.y() * c.x(),
                    h.x() * ay + h.y() * ax)) {
        return false;
      }
    }
    return true;
  }

 private:
  /// The triangle's interval [lo, hi] on an axis lies strictly outside the box's
  /// interval [center - r, center + r] there.
  static bool Separated(double lo, double hi, double center, double r) {
    return lo - center > r || hi - center < -r;
  }

  Eigen::Vector3d e_[3];  // edges b - a, c - b, a - c
  Eigen::Vector3d n_;     // (b - a) x (c - a), not normalised; zero when degenerate
  // Triangle intervals: [0] on x, y, z; [1][0] on n_; [2 + j][i] on axis i x e_j.
  Eigen::Vector3d lo_[5];
  Eigen::Vector3d hi_[5];
};

/// Exact separating-axis test of the closed triangle (a, b, c) against the closed
/// axis-aligned box with the given centre and half sizes (13 axes: 3 box faces,
/// the triangle normal, 9 edge cross products). Touching counts as overlap.
inline bool TriangleBoxOverlap(const Eigen::Vector3d& box_center,
                               const Eigen::Vector3d& box_half_size, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return TriangleBoxTester(a, b, c).Overlaps(box_center, box_half_size);
}

}  // namespace occlude::collision
