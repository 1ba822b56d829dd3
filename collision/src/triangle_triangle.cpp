// Triangle-triangle intersection and distance.
//
// Intersection. Let s_i be the signed (unnormalised) distance of A's corner i to
// B's plane and t_j that of B's corner j to A's plane. If all s (or all t) have
// one strict sign, the triangles are apart. Otherwise, unless they are coplanar,
// each triangle cuts the other's plane in a segment, both segments lie on the
// line where the planes meet, and the triangles intersect iff the segments
// overlap. After relabelling each triangle so that its corner 0 is the one alone
// on its side of the other plane (and orienting both so that this corner is on
// the positive side), the overlap reduces to the signs of two orientation
// determinants (the interval test of Guigue and Devillers, derived here from the
// ordering of the four segment ends on the line). Coplanar pairs get a 2D test
// in the projection that drops the normal's dominant axis; there a zero 2D
// orientation counts as contact only together with an exact extent check, since
// nearly collinear edges far apart get orientations that round to zero.
//
// Rounding policy. Decisions are signs of determinants of the input coordinates,
// with no division and no normalisation, so the answer is exact up to rounding;
// nearly parallel planes need no special case. Two quantities get a tolerance:
//  * Coplanarity: a triangle whose three plane values are within
//    kRoundingRel * (largest |coordinate|) * (rounding scale of the normal) of
//    zero lies in the other's plane up to the rounding of its input coordinates
//    (e.g. coplanar faces after a rigid transform), and gets the 2D test.
//  * Slivers: a triangle whose normal is too small to have a trustworthy
//    direction (sin of its corner angle <= sqrt(eps) ~ 1.5e-8) is treated as its
//    longest edge, moving its third corner by <= 1.5e-8 of that edge.
// A thin triangle above that (sin up to 1e-3) keeps its face, but its normal
// direction is only accurate to ~eps / sin, so results involving its plane are
// accurate to that (<= 1.5e-8 of its size) rather than to rounding, and the
// shortcuts that trust the normal are skipped for it.
//
// Distance. When the triangles do not intersect, the closest pair is attained
// between a corner of one and the other triangle (6 cases) or between two edges
// (9 cases); the minimum of those 15 is the distance. Work is saved without
// changing that minimum: a corner-face case counts only when the foot of the
// corner is inside the face (else an edge-edge case is as close) and only for
// the corner nearest the face's plane with its triangle on one side of it (else
// the pair cannot be the closest); and the search stops at the first candidate
// whose slab (the planes through its two points normal to their difference)
// separates the triangles, the optimality condition of a closest pair.
#include "occlude/collision/triangle_triangle.h"

#include <Eigen/Geometry>  // cross
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "occlude/collision/closest_point.h"

namespace occlude::collision {
namespace {

using Vec = Eigen::Vector3d;

constexpr double kEps = std::numeric_limits<double>::epsilon();
/// sin^2 of a corner angle at or below which a triangle is a segment (sliver).
constexpr double kSliverSin2 = kEps;
/// Relative rounding bound (times the largest |coordinate|) for "lies on the
/// plane" and for the contact of two segments.
constexpr double kRoundingRel = 64 * kEps;
/// sin^2 of a corner angle above which a face's normal direction is accurate to
/// rounding (error ~ eps / sin); flatter faces skip the shortcuts that trust it.
constexpr double kWellShapedSin2 = 1e-6;
/// Relative rounding slack (times the largest |coordinate|) of the optimality
/// certificate of a closest pair; a candidate it accepts is optimal to within
/// 2 * sqrt(3) * kCertifyRel * (largest |coordinate|).
constexpr double kCertifyRel = 16 * kEps;

/// A triangle prepared for the tests. Points at the caller's corners.
struct Tri {
  const Vec* v[3] = {nullptr, nullptr, nullptr};
  Vec n = Vec::Zero();       ///< (v1 - v0) x (v2 - v0), not normalised
  double n_abs = 0.0;        ///< sum of |products| forming n: the scale of its rounding
  bool segment = false;      ///< sliver or zero area: treated as edge (e0, e1)
  bool well_shaped = false;  ///< normal direction accurate to rounding
  int e0 = 0;                ///< longest edge, when segment
  int e1 = 1;
};

/// A pair of prepared triangles and their mutual plane values.
struct Pair {
  Tri a;
  Tri b;
  double sa[3] = {0, 0, 0};  ///< b.n . (a_i - b_0): A's corners against B's plane
  double sb[3] = {0, 0, 0};  ///< a.n . (b_j - a_0): B's corners against A's plane
  double scale = 0.0;        ///< largest |coordinate| of the six corners
};

Tri MakeTri(const Vec& c0, const Vec& c1, const Vec& c2) {
  Tri t;
  t.v[0] = &c0;
  t.v[1] = &c1;
  t.v[2] = &c2;
  const Vec u = c1 - c0;
  const Vec w = c2 - c0;
  t.n = u.cross(w);
  const Vec ua = u.cwiseAbs();
  const Vec wa = w.cwiseAbs();
  t.n_abs = ua.sum() * wa.sum() - ua.dot(wa);  // sum over i != j of |u_i w_j|
  const double n2 = t.n.squaredNorm();
  const double uw2 = u.squaredNorm() * w.squaredNorm();
  t.segment = n2 <= kSliverSin2 * uw2;
  t.well_shaped = n2 > kWellShapedSin2 * uw2;
  if (t.segment) {
    const double l01 = u.squaredNorm();
    const double l12 = (c2 - c1).squaredNorm();
    const double l20 = w.squaredNorm();
    if (l12 >= l01 && l12 >= l20) {
      t.e0 = 1;
      t.e1 = 2;
    } else if (l20 >= l01) {
      t.e0 = 2;
      t.e1 = 0;
    }
  }
  return t;
}

/// d[i] = plane.n . (pts_i - plane_0).
void PlaneValues(const Tri& plane, const Tri& pts, double d[3]) {
  for (int i = 0; i < 3; ++i) d[i] = plane.n.dot(*pts.v[i] - *plane.v[0]);
}

Pair MakePair(const Vec& a0, const Vec& a1, const Vec& a2, const Vec& b0, const Vec& b1,
              const Vec& b2) {
  Pair p;
  p.a = MakeTri(a0, a1, a2);
  p.b = MakeTri(b0, b1, b2);
  PlaneValues(p.b, p.a, p.sa);
  PlaneValues(p.a, p.b, p.sb);
  const Vec m = a0.cwiseAbs()
                    .cwiseMax(a1.cwiseAbs())
                    .cwiseMax(a2.cwiseAbs())
                    .cwiseMax(b0.cwiseAbs())
                    .cwiseMax(b1.cwiseAbs())
                    .cwiseMax(b2.cwiseAbs());
  p.scale = m.maxCoeff();
  return p;
}

/// Bound under which a plane value of `plane` counts as zero.
double PlaneTolerance(const Pair& p, const Tri& plane) {
  return kRoundingRel * p.scale * plane.n_abs;
}

bool StrictlyOneSide(const double d[3]) {
  return (d[0] > 0.0 && d[1] > 0.0 && d[2] > 0.0) || (d[0] < 0.0 && d[1] < 0.0 && d[2] < 0.0);
}

double MaxAbs(const double d[3]) {
  return std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])});
}

/// Signed volume (b - a) x (c - a) . (d - a): positive when d lies on the side
/// of plane (a, b, c) that its right-handed normal points to.
double Orient(const Vec& a, const Vec& b, const Vec& c, const Vec& d) {
  return (b - a).cross(c - a).dot(d - a);
}

/// The point where segment [x, y] crosses a plane, from the plane values dx, dy
/// of its ends (which must differ).
Vec Crossing(const Vec& x, const Vec& y, double dx, double dy) {
  return x + (dx / (dx - dy)) * (y - x);
}

// ----- Distance of disjoint triangles: the 15 cases --------------------------

/// Best candidate pair so far.
struct Closest {
  double d2 = std::numeric_limits<double>::infinity();
  Vec pa = Vec::Zero();
  Vec pb = Vec::Zero();
};

void Offer(Closest* best, double d2, const Vec& pa, const Vec& pb) {
  if (d2 < best->d2) {
    best->d2 = d2;
    best->pa = pa;
    best->pb = pb;
  }
}

/// Barycentric frame of a non-segment triangle: the foot of x on its plane is
/// v0 + l1 e1 + l2 e2 with l1 = g1.(x - v0), l2 = g2.(x - v0).
struct FaceFrame {
  Vec e1;
  Vec e2;
  Vec g1;
  Vec g2;
};

FaceFrame MakeFrame(const Tri& t) {
  FaceFrame f;
  f.e1 = *t.v[1] - *t.v[0];
  f.e2 = *t.v[2] - *t.v[0];
  const double n2 = t.n.squaredNorm();
  f.g1 = f.e2.cross(t.n) / n2;
  f.g2 = t.n.cross(f.e1) / n2;
  return f;
}

/// Corners of one triangle whose foot on the face of the other can be the
/// closest point, from their plane values d against that face (tolerance
/// tol): if the corners straddle the plane, none (a corner-face closest pair
/// has the whole triangle on one side); if they are on one side, the nearest
/// one (the others are farther along the normal); if all are on the plane, all.
int CandidateCorners(const double d[3], double tol, int idx[3]) {
  const bool above = d[0] >= -tol && d[1] >= -tol && d[2] >= -tol;
  const bool below = d[0] <= tol && d[1] <= tol && d[2] <= tol;
  if (above && below) {
    idx[0] = 0;
    idx[1] = 1;
    idx[2] = 2;
    return 3;
  }
  if (!above && !below) return 0;
  const double sign = above ? 1.0 : -1.0;
  idx[0] = 0;
  for (int i = 1; i < 3; ++i) {
    if (sign * d[i] < sign * d[idx[0]]) idx[0] = i;
  }
  return 1;
}

/// Offers the corner-face pairs of `corners` against `face` (d: the corners'
/// plane values against it). Only a foot inside the face is offered: when the
/// closest point of the face is on its boundary, an edge-edge case (an edge at
/// the corner against that boundary edge) is at least as close. A segment face
/// has no inside. The foot is rebuilt from its barycentric coordinates, so it
/// lies on the face even when the face is thin and its normal less accurate.
void OfferCornersOnFace(const Pair& p, const Tri& corners, const Tri& face, const double d[3],
                        bool corners_on_a, Closest* best) {
  if (face.segment) return;
  int idx[3] = {0, 1, 2};
  const int count = face.well_shaped ? CandidateCorners(d, PlaneTolerance(p, face), idx) : 3;
  if (count == 0) return;
  const FaceFrame f = MakeFrame(face);
  for (int k = 0; k < count; ++k) {
    const Vec& x = *corners.v[idx[k]];
    const Vec r = x - *face.v[0];
    const double l1 = f.g1.dot(r);
    const double l2 = f.g2.dot(r);
    if (l1 < 0.0 || l2 < 0.0 || l1 + l2 > 1.0) continue;
    const Vec q = *face.v[0] + l1 * f.e1 + l2 * f.e2;
    const double d2 = (x - q).squaredNorm();
    if (corners_on_a) {
      Offer(best, d2, x, q);
    } else {
      Offer(best, d2, q, x);
    }
  }
}

/// True when the slab between the planes through best.pa and best.pb normal
/// to v = pb - pa separates A from B (up to rounding): then |v| is the
/// distance (the optimality condition of the closest pair of convex sets).
bool Certified(const Pair& p, const Closest& best) {
  const Vec v = best.pb - best.pa;
  const double tol = kCertifyRel * p.scale * v.lpNorm<1>();
  for (int i = 0; i < 3; ++i) {
    if (v.dot(*p.a.v[i] - best.pa) > tol) return false;
    if (v.dot(*p.b.v[i] - best.pb) < -tol) return false;
  }
  return true;
}

TriangleDistance Result(const Closest& best) {
  TriangleDistance r;
  r.p_a = best.pa;
  r.p_b = best.pb;
  r.distance = (best.pa - best.pb).norm();
  return r;
}

/// The edge pair (i * 3 + j: edge i of A, edge j of B) whose midpoints are
/// nearest: usually the closest pair, tried first so that it is certified early.
int LikelyEdgePair(const Pair& p) {
  Vec ma[3];
  Vec mb[3];
  for (int i = 0; i < 3; ++i) {
    ma[i] = *p.a.v[i] + *p.a.v[(i + 1) % 3];  // twice the midpoints: same order
    mb[i] = *p.b.v[i] + *p.b.v[(i + 1) % 3];
  }
  int best = 0;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double d2 = (ma[i] - mb[j]).squaredNorm();
      best = d2 < best_d2 ? i * 3 + j : best;
      best_d2 = std::min(best_d2, d2);
    }
  }
  return best;
}

/// Offers the closest points of edge i of A and edge j of B; true when they
/// become the best pair and are certified optimal.
bool OfferEdgeEdge(const Pair& p, int i, int j, Closest* best) {
  const Vec& a0 = *p.a.v[i];
  const Vec& a1 = *p.a.v[(i + 1) % 3];
  const Vec& b0 = *p.b.v[j];
  const Vec& b1 = *p.b.v[(j + 1) % 3];
  double s = 0.0;
  double t = 0.0;
  const double d2 = ClosestPointsSegmentSegment(a0, a1, b0, b1, &s, &t);
  if (d2 >= best->d2) return false;
  Offer(best, d2, a0 + s * (a1 - a0), b0 + t * (b1 - b0));
  return Certified(p, *best);
}

/// Minimum over the corner-face and edge-edge cases: the distance of disjoint
/// triangles. Stops early when a candidate is certified optimal.
TriangleDistance ClosestPair(const Pair& p) {
  Closest best;
  OfferCornersOnFace(p, p.a, p.b, p.sa, /*corners_on_a=*/true, &best);
  OfferCornersOnFace(p, p.b, p.a, p.sb, /*corners_on_a=*/false, &best);
  if (best.d2 < std::numeric_limits<double>::infinity() && Certified(p, best)) {
    return Result(best);
  }
  const int first = LikelyEdgePair(p);
  if (OfferEdgeEdge(p, first / 3, first % 3, &best)) return Result(best);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i * 3 + j != first && OfferEdgeEdge(p, i, j, &best)) return Result(best);
    }
  }
  return Result(best);
}

/// Records an intersection whose common point is x.
void SetContact(TriangleDistance* out, const Vec& x) {
  out->distance = 0.0;
  out->p_a = x;
  out->p_b = x;
  out->intersecting = true;
}

/// Records an intersection whose common point comes from the 15 cases (valid
/// when the intersection has a corner of one triangle on the other or two
/// crossing edges: coplanar pairs, two segments).
void SetContactFromClosestPair(const Pair& p, TriangleDistance* out) {
  *out = ClosestPair(p);
  out->distance = 0.0;
  out->intersecting = true;
}

// ----- Coplanar case: 2D tests in a coordinate plane ------------------------

struct P2 {
  double x;
  double y;
};

double Orient2(const P2& a, const P2& b, const P2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

int Sign(double x) { return (x > 0.0) - (x < 0.0); }

/// True when c lies in the axis-aligned box of [a, b] (exact comparisons).
/// Given that c is on the line through a and b, this is "c on the segment".
bool InBox(const P2& a, const P2& b, const P2& c) {
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}

/// Closed segments [p, q] and [r, s]; either may be a point. They meet iff they
/// cross strictly (each one's ends on opposite strict sides of the other's line)
/// or an end of one lies on the other. An orientation that is zero only says
/// that the end is on the other's line (up to rounding: nearly collinear
/// segments get orientations that round to zero or to either sign), so it counts
/// only with the end inside the other segment's extent (collinear segments, all
/// four zero, meet iff an end of one lies in the other); and segments whose
/// boxes are disjoint never meet, whatever the rounded signs.
bool Segments2DIntersect(const P2& p, const P2& q, const P2& r, const P2& s) {
  if (std::max(p.x, q.x) < std::min(r.x, s.x) || std::max(r.x, s.x) < std::min(p.x, q.x) ||
      std::max(p.y, q.y) < std::min(r.y, s.y) || std::max(r.y, s.y) < std::min(p.y, q.y)) {
    return false;
  }
  const int o1 = Sign(Orient2(p, q, r));
  const int o2 = Sign(Orient2(p, q, s));
  const int o3 = Sign(Orient2(r, s, p));
  const int o4 = Sign(Orient2(r, s, q));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && InBox(p, q, r)) || (o2 == 0 && InBox(p, q, s)) ||
         (o3 == 0 && InBox(r, s, p)) || (o4 == 0 && InBox(r, s, q));
}

/// p in the closed triangle t; t must have non-zero area.
bool PointIn2DTriangle(const P2& p, const P2 t[3]) {
  const double o0 = Orient2(t[0], t[1], p);
  const double o1 = Orient2(t[1], t[2], p);
  const double o2 = Orient2(t[2], t[0], p);
  return (o0 >= 0.0 && o1 >= 0.0 && o2 >= 0.0) || (o0 <= 0.0 && o1 <= 0.0 && o2 <= 0.0);
}

/// Closed 2D triangles, either possibly degenerate: they meet iff two edges
/// meet or one contains the other (then it contains any corner of the other).
bool Triangles2DIntersect(const P2 a[3], const P2 b[3]) {
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (Segments2DIntersect(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3])) return true;
    }
  }
  if (Orient2(b[0], b[1], b[2]) != 0.0 && PointIn2DTriangle(a[0], b)) return true;
  return Orient2(a[0], a[1], a[2]) != 0.0 && PointIn2DTriangle(b[0], a);
}

/// Test for triangles lying in one plane with normal `normal`.
bool CoplanarIntersect(const Pair& p, const Vec& normal, TriangleDistance* out) {
  Eigen::Index drop = 0;
  normal.cwiseAbs().maxCoeff(&drop);
  const int u = static_cast<int>(drop + 1) % 3;
  const int w = static_cast<int>(drop + 2) % 3;
  P2 a2[3];
  P2 b2[3];
  for (int i = 0; i < 3; ++i) {
    a2[i] = {(*p.a.v[i])[u], (*p.a.v[i])[w]};
    b2[i] = {(*p.b.v[i])[u], (*p.b.v[i])[w]};
  }
  if (!Triangles2DIntersect(a2, b2)) return false;
  if (out != nullptr) SetContactFromClosestPair(p, out);
  return true;
}

// ----- Degenerate triangles -------------------------------------------------

/// One triangle is a segment (seg_is_a says which), the other is proper.
bool SegmentTriangleIntersect(const Pair& p, bool seg_is_a, TriangleDistance* out) {
  const Tri& seg = seg_is_a ? p.a : p.b;
  const Tri& tri = seg_is_a ? p.b : p.a;
  const double* d = seg_is_a ? p.sa : p.sb;
  const Vec& x = *seg.v[seg.e0];
  const Vec& y = *seg.v[seg.e1];
  const double dx = d[seg.e0];
  const double dy = d[seg.e1];
  const double tol = PlaneTolerance(p, tri);
  if (std::abs(dx) <= tol && std::abs(dy) <= tol) return CoplanarIntersect(p, tri.n, out);
  if ((dx > 0.0 && dy > 0.0) || (dx < 0.0 && dy < 0.0)) return false;
  // The segment reaches the plane; its line meets the closed triangle iff the
  // three edge orientations around the line agree.
  const double o0 = Orient(x, y, *tri.v[0], *tri.v[1]);
  const double o1 = Orient(x, y, *tri.v[1], *tri.v[2]);
  const double o2 = Orient(x, y, *tri.v[2], *tri.v[0]);
  if (o0 == 0.0 && o1 == 0.0 && o2 == 0.0) return CoplanarIntersect(p, tri.n, out);
  const bool inside =
      (o0 >= 0.0 && o1 >= 0.0 && o2 >= 0.0) || (o0 <= 0.0 && o1 <= 0.0 && o2 <= 0.0);
  if (!inside) return false;
  if (out != nullptr) SetContact(out, Crossing(x, y, dx, dy));
  return true;
}

/// Both triangles are segments (or points): they meet when their closest
/// points coincide up to the rounding of the coordinates.
bool SegmentSegmentIntersect(const Pair& p, TriangleDistance* out) {
  const TriangleDistance c = ClosestPair(p);
  if (c.distance > kRoundingRel * p.scale) return false;
  if (out != nullptr) SetContactFromClosestPair(p, out);
  return true;
}

// ----- General position: the interval test ----------------------------------

/// Index k of the corner alone on its side of the other plane, given the plane
/// values d (not all of one strict sign, not all zero); returns that side
/// (+1/-1). When two corners share a strict side and the third is on the plane,
/// the third is the lone corner, on the opposite side.
int LoneCorner(const double d[3], int* k) {
  int pos = 0;
  int neg = 0;
  int i_pos = 0;
  int i_neg = 0;
  int i_zero = 0;
  for (int i = 0; i < 3; ++i) {
    if (d[i] > 0.0) {
      ++pos;
      i_pos = i;
    } else if (d[i] < 0.0) {
      ++neg;
      i_neg = i;
    } else {
      i_zero = i;
    }
  }
  if (pos == 1) {
    *k = i_pos;
    return 1;
  }
  if (neg == 1) {
    *k = i_neg;
    return -1;
  }
  *k = i_zero;
  return pos == 2 ? -1 : 1;
}

/// Non-coplanar proper triangles whose corners straddle (or touch) each
/// other's plane. Relabels A as p (p0 alone, on the positive side of B) and B as
/// q (q0 alone, positive side of A). On the planes' common line, directed by
/// nB x nA, A covers [i, j] with i on p0p1, j on p0p2, and B covers [l, k] with
/// k on q0q1, l on q0q2. They overlap iff i <= k and l <= j, which are the
/// signs of Orient(p0, p1, q0, q1) and Orient(p0, p2, q0, q2).
bool CrossingIntersect(const Pair& pr, TriangleDistance* out) {
  int ka = 0;
  int kb = 0;
  const int side_a = LoneCorner(pr.sa, &ka);
  const int side_b = LoneCorner(pr.sb, &kb);
  const Vec* p[3];
  const Vec* q[3];
  double ps[3];
  double qs[3];
  for (int i = 0; i < 3; ++i) {
    p[i] = pr.a.v[(ka + i) % 3];
    ps[i] = pr.sa[(ka + i) % 3];
    q[i] = pr.b.v[(kb + i) % 3];
    qs[i] = pr.sb[(kb + i) % 3];
  }
  if (side_a < 0) {  // flip B so that p0 is on the positive side of its plane
    std::swap(q[1], q[2]);
    std::swap(qs[1], qs[2]);
  }
  if (side_b < 0) {  // flip A likewise for q0
    std::swap(p[1], p[2]);
    std::swap(ps[1], ps[2]);
  }
  if (Orient(*p[0], *p[1], *q[0], *q[1]) > 0.0) return false;  // k < i
  if (Orient(*p[0], *p[2], *q[0], *q[2]) < 0.0) return false;  // j < l
  if (out != nullptr) {
    // The overlap is [max(i, l), min(j, k)]; report its midpoint.
    const Vec start = Orient(*p[0], *p[1], *q[0], *q[2]) > 0.0
                          ? Crossing(*p[0], *p[1], ps[0], ps[1])   // l < i
                          : Crossing(*q[0], *q[2], qs[0], qs[2]);  // i <= l
    const Vec end = Orient(*p[0], *p[2], *q[0], *q[1]) <= 0.0
                        ? Crossing(*p[0], *p[2], ps[0], ps[2])   // j <= k
                        : Crossing(*q[0], *q[1], qs[0], qs[1]);  // k < j
    SetContact(out, 0.5 * (start + end));
  }
  return true;
}

/// The intersection test on a prepared pair; fills *out (when non-null) with a
/// common point when the triangles intersect.
bool Intersect(const Pair& p, TriangleDistance* out) {
  if (p.a.segment && p.b.segment) return SegmentSegmentIntersect(p, out);
  if (p.a.segment || p.b.segment) return SegmentTriangleIntersect(p, p.a.segment, out);
  const double tol_b = PlaneTolerance(p, p.b);  // for p.sa
  const double tol_a = PlaneTolerance(p, p.a);  // for p.sb
  const double max_sa = MaxAbs(p.sa);
  const double max_sb = MaxAbs(p.sb);
  if (StrictlyOneSide(p.sa) && max_sa > tol_b) return false;
  if (StrictlyOneSide(p.sb) && max_sb > tol_a) return false;
  if (max_sb <= tol_a) return CoplanarIntersect(p, p.a.n, out);
  if (max_sa <= tol_b) return CoplanarIntersect(p, p.b.n, out);
  return CrossingIntersect(p, out);
}

/// Smallest |d| when all d share one strict sign, else 0.
double PlaneGap(const double d[3]) {
  if (d[0] > 0.0 && d[1] > 0.0 && d[2] > 0.0) return std::min({d[0], d[1], d[2]});
  if (d[0] < 0.0 && d[1] < 0.0 && d[2] < 0.0) return -std::max({d[0], d[1], d[2]});
  return 0.0;
}

/// True when `plane` proves the other triangle (plane values d) farther than
/// sqrt(max_distance2); writes that lower bound of the distance to *bound.
bool PlaneSeparates(const Pair& p, const Tri& plane, const double d[3], double max_distance2,
                    double* bound) {
  if (!plane.well_shaped) return false;  // normal direction not trusted enough
  const double gap = PlaneGap(d);
  const double n2 = plane.n.squaredNorm();
  if (gap * gap <= max_distance2 * n2 || gap <= PlaneTolerance(p, plane)) return false;
  *bound = gap / std::sqrt(n2);
  return true;
}

/// Records an early rejection: distance becomes a lower bound > max_distance.
void SetApart(TriangleDistance* out, double lower_bound, double max_distance) {
  out->distance =
      std::max(lower_bound, std::nextafter(max_distance, std::numeric_limits<double>::infinity()));
  out->intersecting = false;
}

}  // namespace

bool TrianglesIntersect(const Vec& a0, const Vec& a1, const Vec& a2, const Vec& b0, const Vec& b1,
                        const Vec& b2) {
  return Intersect(MakePair(a0, a1, a2, b0, b1, b2), nullptr);
}

TriangleDistance TriangleTriangleDistance(const Vec& a0, const Vec& a1, const Vec& a2,
                                          const Vec& b0, const Vec& b1, const Vec& b2) {
  const Pair p = MakePair(a0, a1, a2, b0, b1, b2);
  TriangleDistance r;
  if (Intersect(p, &r)) return r;
  return ClosestPair(p);
}

bool TrianglesWithin(const Vec& a0, const Vec& a1, const Vec& a2, const Vec& b0, const Vec& b1,
                     const Vec& b2, double max_distance, TriangleDistance* out) {
  TriangleDistance local;
  TriangleDistance* r = out != nullptr ? out : &local;
  if (!(max_distance >= 0.0)) {  // negative or NaN: nothing is that close
    *r = TriangleTriangleDistance(a0, a1, a2, b0, b1, b2);
    return false;
  }
  const double md2 = max_distance * max_distance;
  const Vec lo_a = a0.cwiseMin(a1).cwiseMin(a2);
  const Vec hi_a = a0.cwiseMax(a1).cwiseMax(a2);
  const Vec lo_b = b0.cwiseMin(b1).cwiseMin(b2);
  const Vec hi_b = b0.cwiseMax(b1).cwiseMax(b2);
  const double box_gap2 = (lo_b - hi_a).cwiseMax(lo_a - hi_b).cwiseMax(0.0).squaredNorm();
  if (box_gap2 > md2) {
    SetApart(r, std::sqrt(box_gap2), max_distance);
    return false;
  }
  const Pair p = MakePair(a0, a1, a2, b0, b1, b2);
  double bound = 0.0;
  if (PlaneSeparates(p, p.a, p.sb, md2, &bound) || PlaneSeparates(p, p.b, p.sa, md2, &bound)) {
    SetApart(r, bound, max_distance);
    return false;
  }
  if (Intersect(p, r)) return true;
  *r = ClosestPair(p);
  return r->distance <= max_distance;
}

}  // namespace occlude::collision
