// The optimized-sphere lookup table: for each child-occupancy mask, the
// minimum enclosing sphere of the corners of the occupied child cubes,
// computed with Welzl's algorithm once per process.
#include "occlude/collision/sphere_table.h"

#include <Eigen/Dense>
#include <vector>

namespace occlude::collision {
namespace {

constexpr double kContainSlack = 1e-12;

bool Contains(const UnitSphere& s, const Eigen::Vector3d& p) {
  return (p - s.center).norm() <= s.radius + kContainSlack;
}

UnitSphere FromTwo(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return {0.5 * (a + b), 0.5 * (a - b).norm()};
}

UnitSphere FromThree(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  const Eigen::Vector3d n = ab.cross(ac);
  const double n2 = n.squaredNorm();
  if (n2 < 1e-24) {  // collinear: the two farthest points span the ball
    UnitSphere best = FromTwo(a, b);
    for (const UnitSphere& cand : {FromTwo(a, c), FromTwo(b, c)}) {
      if (cand.radius > best.radius) best = cand;
    }
    return best;
  }
  const Eigen::Vector3d offset =
      (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / (2.0 * n2);
  return {a + offset, offset.norm()};
}

UnitSphere FromFour(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d) {
  Eigen::Matrix3d m;
  m.row(0) = (b - a).transpose();
  m.row(1) = (c - a).transpose();
  m.row(2) = (d - a).transpose();
  const double det = m.determinant();
  if (std::abs(det) < 1e-18) return FromThree(a, b, c);  // coplanar boundary points are cocircular
  const Eigen::Vector3d rhs(0.5 * (b - a).squaredNorm(), 0.5 * (c - a).squaredNorm(),
                            0.5 * (d - a).squaredNorm());
  const Eigen::Vector3d offset = m.partialPivLu().solve(rhs);
  return {a + offset, offset.norm()};
}

UnitSphere FromBoundary(const std::vector<Eigen::Vector3d>& r) {
  switch (r.size()) {
    case 0:
      return {Eigen::Vector3d::Zero(), -1.0};  // contains nothing
    case 1:
      return {r[0], 0.0};
    case 2:
      return FromTwo(r[0], r[1]);
    case 3:
      return FromThree(r[0], r[1], r[2]);
    default:
      return FromFour(r[0], r[1], r[2], r[3]);
  }
}

// Welzl: smallest sphere enclosing points[0..n) with every point of `boundary` on it.
UnitSphere Welzl(const Eigen::Vector3d* points, int n, std::vector<Eigen::Vector3d>* boundary) {
  if (n == 0 || boundary->size() == 4) return FromBoundary(*boundary);
  const Eigen::Vector3d& p = points[n - 1];
  UnitSphere ball = Welzl(points, n - 1, boundary);
  if (ball.radius >= 0.0 && Contains(ball, p)) return ball;
  boundary->push_back(p);
  ball = Welzl(points, n - 1, boundary);
  boundary->pop_back();
  return ball;
}

std::array<UnitSphere, 256> ComputeTable() {
  std::array<UnitSphere, 256> table{};
  table[0] = {Eigen::Vector3d::Zero(), kCubeCircumradius};
  for (int mask = 1; mask < 256; ++mask) {
    // Corners of the occupied child cubes lie on the lattice {-1/2, 0, 1/2}^3.
    bool used[27] = {};
    for (int slot = 0; slot < 8; ++slot) {
      if (!(mask & (1 << slot))) continue;
      const Eigen::Vector3i lo((slot & 1), (slot >> 1) & 1, (slot >> 2) & 1);
      for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3i q =
            lo + Eigen::Vector3i(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        used[q.x() + 3 * q.y() + 9 * q.z()] = true;
      }
    }
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < 27; ++i) {
      const Eigen::Vector3i cell(i % 3, (i / 3) % 3, i / 9);
      if (used[i]) pts.push_back(0.5 * cell.cast<double>() - Eigen::Vector3d::Constant(0.5));
    }
    table[static_cast<std::size_t>(mask)] =
        MinimumEnclosingSphere(pts.data(), static_cast<int>(pts.size()));
  }
  return table;
}

}  // namespace

UnitSphere MinimumEnclosingSphere(const Eigen::Vector3d* points, int count) {
  std::vector<Eigen::Vector3d> boundary;
  boundary.reserve(4);
  return Welzl(points, count, &boundary);
}

const std::array<UnitSphere, 256>& OptimizedSphereTable() {
  static const std::array<UnitSphere, 256> table = ComputeTable();
  return table;
}

}  // namespace occlude::collision
