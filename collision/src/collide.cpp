// The simultaneous depth-first descent of two sphere trees.
//
// Each stack entry is a node pair whose spheres already passed the test. The
// larger node (by edge) is split: each occupied child's sphere is derived
// (implicit modes: from the parent's cube centre plus the rotated child offset
// s*2^(L-2), see sphere_table.h; explicit mode: stored centre moved into A) and
// tested against the other node's sphere; passing pairs are pushed. Two leaves
// get the exact grown-cube test, computed from integer voxel coordinates in
// every mode, so all modes report identical pairs.
//
// Stack bound: splitting one node pushes at most 8 entries and removes one, and
// each split lowers one of the two levels, so the stack never exceeds
// 1 + 7 * (top_a + top_b + 1) entries.
#include "occlude/collision/collide.h"

#include <cmath>
#include <stdexcept>

#include "collide_exact.h"
#include "occlude/collision/sphere_table.h"

namespace occlude::collision {
namespace {

constexpr double kPruneSlackMm = 1e-9;  // keeps rounding from pruning a valid pair

// One tree as seen from frame A during a query.
struct Side {
  const SphereTree* tree;
  const Octree* oct;
  Eigen::Matrix3d R;      // rotation of this tree's frame into A
  Eigen::Vector3d t;      // translation of this tree's frame into A
  Eigen::Vector3d slot_dir[8];  // R * ChildSlotSign(k)
  double s;               // voxel size
  bool rotated;

  Side(const SphereTree& tr, const Eigen::Isometry3d& X, bool is_rotated)
      : tree(&tr), oct(&tr.octree()), R(X.linear()), t(X.translation()),
        s(tr.voxel_size_mm()), rotated(is_rotated) {
    for (int k = 0; k < 8; ++k) slot_dir[k] = R * ChildSlotSign(k);
  }
  Eigen::Vector3d ToA(const Eigen::Vector3d& p) const { return rotated ? Eigen::Vector3d(R * p + t) : p; }
  Eigen::Vector3d DirToA(const Eigen::Vector3d& v) const { return rotated ? Eigen::Vector3d(R * v) : v; }
  // Voxel centre in A, from integer coordinates (identical in every mode).
  Eigen::Vector3d VoxelCenterA(std::uint32_t leaf_node) const {
    return ToA(tree->CubeCenter(leaf_node, 0));
  }
};

// A node on the stack: index, level, and a centre in A whose meaning depends on
// the mode (cube centre for implicit modes, sphere centre for explicit).
struct NodeRef {
  std::uint32_t node;
  int level;
  Eigen::Vector3d center;
};
struct Entry {
  NodeRef a, b;
};

// Sphere of a node (centre in A, radius) for each mode.
template <SphereMode kMode>
struct Spheres;

template <>
struct Spheres<SphereMode::kSimple> {
  static NodeRef Root(const Side& s) {
    return {0, s.oct->top_level, s.ToA(s.tree->CubeCenter(0, s.oct->top_level))};
  }
  static void Sphere(const Side& s, const NodeRef& n, Eigen::Vector3d* c, double* r) {
    *c = n.center;
    *r = SimpleRadius(s.tree->edge(n.level));
  }
  static NodeRef Child(const Side& s, const NodeRef& parent, std::uint32_t child, int slot) {
    return {child, parent.level - 1,
            parent.center + ChildCenterOffset(s.s, parent.level) * s.slot_dir[slot]};
  }
};

template <>
struct Spheres<SphereMode::kOptimized> {
  static NodeRef Root(const Side& s) { return Spheres<SphereMode::kSimple>::Root(s); }
  static void Sphere(const Side& s, const NodeRef& n, Eigen::Vector3d* c, double* r) {
    const UnitSphere& u = OptimizedSphereTable()[s.oct->child_mask[n.node]];
    const double e = s.tree->edge(n.level);
    *c = n.center + e * s.DirToA(u.center);
    *r = e * u.radius;
  }
  static NodeRef Child(const Side& s, const NodeRef& parent, std::uint32_t child, int slot) {
    return Spheres<SphereMode::kSimple>::Child(s, parent, child, slot);
  }
};

template <>
struct Spheres<SphereMode::kExplicit> {
  static NodeRef At(const Side& s, std::uint32_t node, int level) {
    const ExplicitSpheres& ex = s.tree->explicit_spheres();
    return {node, level, s.ToA(Eigen::Vector3d(ex.cx[node], ex.cy[node], ex.cz[node]))};
  }
  static NodeRef Root(const Side& s) { return At(s, 0, s.oct->top_level); }
  static void Sphere(const Side& s, const NodeRef& n, Eigen::Vector3d* c, double* r) {
    *c = n.center;
    *r = s.tree->explicit_spheres().radius[n.node];
  }
  static NodeRef Child(const Side& s, const NodeRef& parent, std::uint32_t child, int /*slot*/) {
    return At(s, child, parent.level - 1);
  }
};

class Traversal {
 public:
  Traversal(const Side& a, const Side& b, const CollisionRequest& req, CollisionResult* res)
      : a_(a), b_(b), req_(req), res_(res),
        grow_sphere_(kCubeCircumradius * req.delta_mm),
        h_a_(0.5 * a.s), h_b_(0.5 * b.s) {}

  template <SphereMode kMode>
  void Run(std::vector<Entry>* stack) {
    using S = Spheres<kMode>;
    stack->clear();
    const Entry root{S::Root(a_), S::Root(b_)};
    if (!SpheresOverlap<kMode>(root.a, root.b)) return;
    stack->push_back(root);
    while (!stack->empty()) {
      const Entry e = stack->back();
      stack->pop_back();
      if (e.a.level == 0 && e.b.level == 0) {
        if (LeafPair(e) && req_.first_only) return;
        continue;
      }
      const bool split_a = e.b.level == 0 ||
                           (e.a.level > 0 && a_.tree->edge(e.a.level) >= b_.tree->edge(e.b.level));
      if (split_a) {
        if (!Split<kMode>(a_, e.a, e.b, true, stack)) return;
      } else {
        if (!Split<kMode>(b_, e.b, e.a, false, stack)) return;
      }
    }
  }

 private:
  template <SphereMode kMode>
  bool SpheresOverlap(const NodeRef& na, const NodeRef& nb) {
    ++res_->node_tests;
    Eigen::Vector3d ca, cb;
    double ra = 0.0, rb = 0.0;
    Spheres<kMode>::Sphere(a_, na, &ca, &ra);
    Spheres<kMode>::Sphere(b_, nb, &cb, &rb);
    const double reach = ra + rb + 2.0 * grow_sphere_ + kPruneSlackMm;
    return (ca - cb).squaredNorm() <= reach * reach;
  }

  // Splits `node` (of `side`) against `other`; returns false when the budget ran out.
  template <SphereMode kMode>
  bool Split(const Side& side, const NodeRef& node, const NodeRef& other, bool node_is_a,
             std::vector<Entry>* stack) {
    const Octree& oct = *side.oct;
    std::uint32_t child = oct.first_child[node.node];
    for (unsigned mask = oct.child_mask[node.node]; mask != 0; mask &= mask - 1, ++child) {
      if (req_.max_node_tests != 0 && res_->node_tests >= req_.max_node_tests) {
        res_->complete = false;
        return false;
      }
      const int slot = __builtin_ctz(mask);
      const NodeRef c = Spheres<kMode>::Child(side, node, child, slot);
      const bool hit = node_is_a ? SpheresOverlap<kMode>(c, other) : SpheresOverlap<kMode>(other, c);
      if (hit) stack->push_back(node_is_a ? Entry{c, other} : Entry{other, c});
    }
    return true;
  }

  bool LeafPair(const Entry& e) {
    ++res_->leaf_tests;
    const Eigen::Vector3d ca = a_.VoxelCenterA(e.a.node);
    const Eigen::Vector3d cb = b_.VoxelCenterA(e.b.node);
    if (!GrownCubesOverlap(ca, h_a_, cb, h_b_, b_.R, 0.5 * req_.delta_mm)) return false;
    res_->overlap = true;
    res_->pairs.push_back({e.a.node - a_.oct->leaf_begin(), e.b.node - b_.oct->leaf_begin()});
    return true;
  }

  const Side& a_;
  const Side& b_;
  const CollisionRequest& req_;
  CollisionResult* res_;
  double grow_sphere_;
  double h_a_, h_b_;
};

void Validate(const Eigen::Isometry3d& X_AB, const CollisionRequest& request) {
  if (!(request.delta_mm >= 0.0) || !std::isfinite(request.delta_mm)) {
    throw std::invalid_argument("CollisionRequest.delta_mm must be finite and >= 0");
  }
  if (!X_AB.matrix().allFinite()) throw std::invalid_argument("X_AB has non-finite entries");
  const Eigen::Matrix3d RtR = X_AB.linear().transpose() * X_AB.linear();
  if (!RtR.isApprox(Eigen::Matrix3d::Identity(), 1e-6) || X_AB.linear().determinant() < 0) {
    throw std::invalid_argument("X_AB is not a rigid transform (rotation not orthonormal)");
  }
}

}  // namespace

void CollisionResult::Clear() {
  overlap = false;
  complete = true;
  node_tests = leaf_tests = triangle_tests = 0;
  pairs.clear();
  contacts.clear();
  triangles_intersect = false;
  min_distance_mm = std::numeric_limits<double>::infinity();
  closest = TriangleContact{};
}

bool GrownCubesOverlap(const Eigen::Vector3d& c_a, double h_a, const Eigen::Vector3d& c_b,
                       double h_b, const Eigen::Matrix3d& R, double grow) {
  constexpr double kParallelSlack = 1e-12;  // keeps near-parallel cross axes conservative
  const double a = h_a + grow;
  const double b = h_b + grow;
  const Eigen::Vector3d T = c_b - c_a;  // in A
  Eigen::Matrix3d absR = R.cwiseAbs().array() + kParallelSlack;
  for (int i = 0; i < 3; ++i) {  // A's face axes
    if (std::abs(T[i]) > a + b * absR.row(i).sum()) return false;
  }
  for (int j = 0; j < 3; ++j) {  // B's face axes
    if (std::abs(T.dot(R.col(j))) > a * absR.col(j).sum() + b) return false;
  }
  for (int i = 0; i < 3; ++i) {  // cross axes A_i x B_j
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = a * (absR(i1, j) + absR(i2, j));
      const double rb = b * (absR(i, j1) + absR(i, j2));
      if (std::abs(T[i2] * R(i1, j) - T[i1] * R(i2, j)) > ra + rb) return false;
    }
  }
  return true;
}

void Collide(const SphereTree& a, const SphereTree& b, const Eigen::Isometry3d& X_AB,
             const CollisionRequest& request, CollisionResult* result) {
  Validate(X_AB, request);
  result->Clear();
  if (a.empty() || b.empty()) return;
  thread_local std::vector<Entry> stack;
  stack.reserve(8 * static_cast<std::size_t>(a.octree().top_level + b.octree().top_level + 2));
  const Side side_a(a, Eigen::Isometry3d::Identity(), false);
  const Side side_b(b, X_AB, true);
  Traversal traversal(side_a, side_b, request, result);
  SphereMode mode = request.spheres;
  if (mode == SphereMode::kExplicit && b.explicit_spheres().empty()) mode = b.explicit_spheres().from;
  if (mode == SphereMode::kExplicit && a.explicit_spheres().empty()) mode = a.explicit_spheres().from;
  switch (mode) {
    case SphereMode::kSimple: traversal.Run<SphereMode::kSimple>(&stack); break;
    case SphereMode::kOptimized: traversal.Run<SphereMode::kOptimized>(&stack); break;
    case SphereMode::kExplicit: traversal.Run<SphereMode::kExplicit>(&stack); break;
  }
  if (request.exact) RefineExact(a, b, X_AB, request.delta_mm, result);
}

bool CollisionPair::Overlap(const Eigen::Isometry3d& X_AB, double delta_mm, SphereMode mode) const {
  CollisionRequest request;
  request.spheres = mode;
  request.delta_mm = delta_mm;
  request.first_only = true;
  thread_local CollisionResult result;
  Collide(a_, b_, X_AB, request, &result);
  return result.overlap;
}

}  // namespace occlude::collision
