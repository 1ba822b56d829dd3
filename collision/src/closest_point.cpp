// Closest-point primitives. The triangle case classifies p against the Voronoi
// regions of the vertices, edges and face in turn, using dot products only, so
// it is exact up to rounding and needs no normalisation.
#include "occlude/collision/closest_point.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace occlude::collision {
namespace {

TrianglePoint Make(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   const Eigen::Vector3d& c, double wa, double wb, double wc) {
  TrianglePoint r;
  r.barycentric = Eigen::Vector3d(wa, wb, wc);
  r.point = wa * a + wb * b + wc * c;
  r.squared_distance = (p - r.point).squaredNorm();
  return r;
}

// Closest point over the three edges (for degenerate and sliver triangles).
TrianglePoint ClosestOnEdges(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  double s = 0.0;
  double t = 0.0;
  TrianglePoint best = Make(p, a, b, c, 1, 0, 0);
  const Eigen::Vector3d* corners[3] = {&a, &b, &c};
  for (int e = 0; e < 3; ++e) {
    const int j = (e + 1) % 3;
    ClosestPointsSegmentSegment(*corners[e], *corners[j], p, p, &s, &t);
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    w[e] = 1 - s;
    w[j] = s;
    const TrianglePoint cand = Make(p, a, b, c, w[0], w[1], w[2]);
    if (cand.squared_distance < best.squared_distance) best = cand;
  }
  return best;
}

}  // namespace

TrianglePoint ClosestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  // Slivers (corner-angle sine below ~1e-6) make the Voronoi products below
  // cancel catastrophically; their closest point is on an edge to within
  // sine * edge length, so the exact edge search is used instead.
  constexpr double kSliverSine2 = 1e-12;
  if (ab.cross(ac).squaredNorm() <= kSliverSine2 * ab.squaredNorm() * ac.squaredNorm()) {
    return ClosestOnEdges(p, a, b, c);
  }
  const Eigen::Vector3d ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return Make(p, a, b, c, 1, 0, 0);  // vertex a

  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return Make(p, a, b, c, 0, 1, 0);  // vertex b

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) {  // edge ab
    const double v = d1 / (d1 - d3);
    return Make(p, a, b, c, 1 - v, v, 0);
  }

  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return Make(p, a, b, c, 0, 0, 1);  // vertex c

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) {  // edge ac
    const double w = d2 / (d2 - d6);
    return Make(p, a, b, c, 1 - w, 0, w);
  }

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0) {  // edge bc
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return Make(p, a, b, c, 0, 1 - w, w);
  }

  const double sum = va + vb + vc;
  if (sum > 0.0) {  // face interior
    const double v = vb / sum;
    const double w = vc / sum;
    return Make(p, a, b, c, 1 - v - w, v, w);
  }

  return ClosestOnEdges(p, a, b, c);  // degenerate: the closest point is on an edge
}

double ClosestPointsSegmentSegment(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                   const Eigen::Vector3d& q0, const Eigen::Vector3d& q1,
                                   double* s_out, double* t_out) {
  const Eigen::Vector3d d1 = p1 - p0;
  const Eigen::Vector3d d2 = q1 - q0;
  const Eigen::Vector3d r = p0 - q0;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  double s = 0.0;
  double t = 0.0;
  if (a <= 0.0 && e <= 0.0) {
    s = t = 0.0;
  } else if (a <= 0.0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0.0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  *s_out = s;
  *t_out = t;
  return (p0 + s * d1 - (q0 + t * d2)).squaredNorm();
}

}  // namespace occlude::collision
