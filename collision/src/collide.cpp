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

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "collide_exact.h"
#include "occlude/collision/morton.h"
#include "occlude/collision/sphere_table.h"

namespace occlude::collision {
namespace {

constexpr double kPruneSlackMm = 1e-9;  // keeps rounding from pruning a valid pair

// Bits set in a child mask (no popcnt instruction assumed).
constexpr std::array<std::uint8_t, 256> kPopCount8 = [] {
  std::array<std::uint8_t, 256> t{};
  for (int m = 0; m < 256; ++m) {
    t[static_cast<std::size_t>(m)] =
        static_cast<std::uint8_t>((m & 1) + t[static_cast<std::size_t>(m >> 1)]);
  }
  return t;
}();

// One tree as seen from frame A during a query.
constexpr int kMaxLevels = 24;  // Morton codes hold 21 bits per axis
constexpr int kMaxCellLevel = 3;

// Node tests the boolean pair descent may spend before the one-sided descent
// takes over (a-bite-3shape, 0.2 mm: near contact the closest-first pair
// descent needs 240-900 in optimized / explicit mode; far apart 10^4-10^5;
// 400, 800, 1500 and 4000 measured, 800 best overall).
constexpr std::size_t kTrialBudget = 800;

struct Side {
  const SphereTree* tree;
  const Octree* oct;
  const UnitSphere* table;      // OptimizedSphereTable()
  const ExplicitNode* ex;       // explicit records (null when not built)
  const DistanceBound* bound;   // null when not built
  Eigen::Matrix3d R;            // rotation of this tree's frame into A
  Eigen::Vector3d t;            // translation of this tree's frame into A
  Eigen::Vector3d slot_dir[8];  // R * ChildSlotSign(k)
  double s;                     // voxel size
  bool rotated;
  double edge[kMaxLevels] = {};           // node edge per level
  double simple_radius[kMaxLevels] = {};  // sqrt(3)/2 * edge
  double child_offset[kMaxLevels] = {};   // ChildCenterOffset(s, level)

  Side(const SphereTree& tr, const Eigen::Isometry3d& X, bool is_rotated)
      : tree(&tr),
        oct(&tr.octree()),
        table(OptimizedSphereTable().data()),
        ex(tr.explicit_spheres().nodes.empty() ? nullptr : tr.explicit_spheres().nodes.data()),
        bound(tr.distance_bound().empty() ? nullptr : &tr.distance_bound()),
        R(X.linear()),
        t(X.translation()),
        s(tr.voxel_size_mm()),
        rotated(is_rotated) {
    for (int k = 0; k < 8; ++k) slot_dir[k] = R * ChildSlotSign(k);
    for (int level = 0; level < kMaxLevels; ++level) {
      edge[level] = tr.edge(level);
      simple_radius[level] = SimpleRadius(edge[level]);
      child_offset[level] = ChildCenterOffset(s, level);
    }
  }
  Eigen::Vector3d ToA(const Eigen::Vector3d& p) const {
    return rotated ? Eigen::Vector3d(R * p + t) : p;
  }
  Eigen::Vector3d DirToA(const Eigen::Vector3d& v) const {
    return rotated ? Eigen::Vector3d(R * v) : v;
  }
  Eigen::Vector3d FromA(const Eigen::Vector3d& p) const {
    return rotated ? Eigen::Vector3d(R.transpose() * (p - t)) : p;
  }
  // True when this tree's bound proves every one of its voxel cubes farther
  // than `radius` from p_A (a point in A).
  bool Excludes(const Eigen::Vector3d& p_A, double radius) const {
    return bound != nullptr && bound->Excludes(FromA(p_A), radius);
  }
  // Voxel centre in A, from integer coordinates (identical in every mode).
  Eigen::Vector3d VoxelCenterA(std::uint32_t leaf_node) const {
    const Eigen::Vector3d p = tree->grid().origin_F + s * (oct->coord[leaf_node].cast<double>() +
                                                           Eigen::Vector3d::Constant(0.5));
    return ToA(p);
  }
};

// The separating-axis test of two cubes (A axis-aligned, B with axes R), each
// grown by `grow`, with everything that depends only on the query precomputed:
// the cubes have fixed sizes, so all 15 projection radii are constants.
class CubePairTest {
 public:
  CubePairTest(double h_a, double h_b, const Eigen::Matrix3d& R, double grow) : R_(R) {
    constexpr double kParallelSlack = 1e-12;  // keeps near-parallel cross axes conservative
    const double a = h_a + grow;
    const double b = h_b + grow;
    const Eigen::Matrix3d absR = R.cwiseAbs().array() + kParallelSlack;
    for (int i = 0; i < 3; ++i) {
      face_a_[i] = a + b * absR.row(i).sum();
      face_b_[i] = a * absR.col(i).sum() + b;
    }
    for (int i = 0; i < 3; ++i) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
      for (int j = 0; j < 3; ++j) {
        const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        cross_[i][j] = a * (absR(i1, j) + absR(i2, j)) + b * (absR(i, j1) + absR(i, j2));
      }
    }
  }
  /// T = centre of B minus centre of A, in A.
  bool Overlap(const Eigen::Vector3d& T) const {
    for (int i = 0; i < 3; ++i) {
      if (std::abs(T[i]) > face_a_[i]) return false;
    }
    for (int j = 0; j < 3; ++j) {
      if (std::abs(T.dot(R_.col(j))) > face_b_[j]) return false;
    }
    for (int i = 0; i < 3; ++i) {
      const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
      for (int j = 0; j < 3; ++j) {
        if (std::abs(T[i2] * R_(i1, j) - T[i1] * R_(i2, j)) > cross_[i][j]) return false;
      }
    }
    return true;
  }

 private:
  Eigen::Matrix3d R_;
  double face_a_[3] = {}, face_b_[3] = {}, cross_[3][3] = {};
};

// A node on the stack: index, level, and a centre in A whose meaning depends on
// the mode (cube centre for implicit modes, sphere centre for explicit).
struct NodeRef {
  std::uint32_t node = 0;
  int level = 0;
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
    *r = s.simple_radius[n.level];
  }
  static NodeRef Child(const Side& s, const NodeRef& parent, std::uint32_t child, int slot) {
    return {child, parent.level - 1,
            parent.center + s.child_offset[parent.level] * s.slot_dir[slot]};
  }
};

template <>
struct Spheres<SphereMode::kOptimized> {
  static NodeRef Root(const Side& s) { return Spheres<SphereMode::kSimple>::Root(s); }
  static void Sphere(const Side& s, const NodeRef& n, Eigen::Vector3d* c, double* r) {
    const UnitSphere& u = s.table[s.oct->child_mask[n.node]];
    const double e = s.edge[n.level];
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
    const ExplicitNode& rec = s.ex[node];
    return {node, level, s.ToA(Eigen::Vector3d(rec.cx, rec.cy, rec.cz))};
  }
  static NodeRef Root(const Side& s) { return At(s, 0, s.oct->top_level); }
  static void Sphere(const Side& s, const NodeRef& n, Eigen::Vector3d* c, double* r) {
    *c = n.center;
    *r = s.ex[n.node].radius;
  }
  static NodeRef Child(const Side& s, const NodeRef& parent, std::uint32_t child, int /*slot*/) {
    return At(s, child, parent.level - 1);
  }
};

struct Slab {
  Eigen::Vector3d n;  // unit normal in A
  double lo, hi;      // range of (x - centre) . n over the node's voxels
};

Slab SlabOf(const Side& s, std::uint32_t node) {
  const ExplicitNode& rec = s.ex[node];
  return {s.DirToA(Eigen::Vector3d(static_cast<double>(rec.nx), static_cast<double>(rec.ny),
                                   static_cast<double>(rec.nz))),
          static_cast<double>(rec.slab_lo), static_cast<double>(rec.slab_hi)};
}

// True when node q (sphere c_q, r_q and slab sq) lies entirely outside node p's
// slab (centre c_p, slab sp), by more than tol. For y = x - c_q with |y| <= r_q
// and y.n_q in [lo_q, hi_q]: y.n_p = (y.n_q) cos + y.w with |w| = sin, so
// y.n_p lies in cos*[lo_q, hi_q] widened by r_q*sin, and in [-r_q, r_q].
bool SlabSeparates(const Eigen::Vector3d& c_p, const Slab& sp, const Eigen::Vector3d& c_q,
                   double r_q, const Slab& sq, double tol) {
  const double cosv = sp.n.dot(sq.n);
  const double sinv = std::sqrt(std::max(0.0, 1.0 - cosv * cosv));
  const double base = (c_q - c_p).dot(sp.n);
  const double a = sq.lo * cosv, b = sq.hi * cosv;
  const double q_lo = base + std::max(std::min(a, b) - r_q * sinv, -r_q);
  const double q_hi = base + std::min(std::max(a, b) + r_q * sinv, r_q);
  return q_lo > sp.hi + tol || q_hi < sp.lo - tol;
}

// The node test: spheres (paper eq. 4) grown by `grow_sphere` each, then, in
// explicit mode, the slabs both ways.
template <SphereMode kMode>
bool NodesOverlap(const Side& a, const Side& b, const NodeRef& na, const NodeRef& nb,
                  double grow_sphere) {
  Eigen::Vector3d ca, cb;
  double ra = 0.0, rb = 0.0;
  Spheres<kMode>::Sphere(a, na, &ca, &ra);
  Spheres<kMode>::Sphere(b, nb, &cb, &rb);
  const double reach = ra + rb + 2.0 * grow_sphere + kPruneSlackMm;
  if ((ca - cb).squaredNorm() > reach * reach) return false;
  if constexpr (kMode == SphereMode::kExplicit) {
    const Slab sa = SlabOf(a, na.node);
    const Slab sb = SlabOf(b, nb.node);
    const double tol = 2.0 * grow_sphere + kPruneSlackMm;
    if (SlabSeparates(ca, sa, cb, rb, sb, tol) || SlabSeparates(cb, sb, ca, ra, sa, tol)) {
      return false;
    }
  }
  return true;
}

class Traversal {
 public:
  Traversal(const Side& a, const Side& b, const CollisionRequest& req, CollisionResult* res)
      : a_(a),
        b_(b),
        req_(req),
        res_(res),
        grow_sphere_(kCubeCircumradius * req.delta_mm),
        cube_test_(0.5 * a.s, 0.5 * b.s, b.R, 0.5 * req.delta_mm) {}

  template <SphereMode kMode>
  void Run(std::vector<Entry>* stack) {
    using S = Spheres<kMode>;
    stack->clear();
    const Entry root{S::Root(a_), S::Root(b_)};
    if (!SpheresOverlap<kMode>(root.a, root.b)) return;
    stack->push_back(root);
    Descend<kMode>(stack);
  }

  /// The boolean query with A's distance bound: B is descended alone, each
  /// node pruned when A's bound proves it out of reach of every A voxel; a B
  /// node that survives down to `pair_level` is resolved by the pair descent
  /// of (A's root, that node), which finds the exact pairs. Every B voxel with
  /// a pair survives (the bound is conservative), so the answer is the same as
  /// Run's. Far apart (no pair), the cost is the B nodes near A, each tested in
  /// O(1) against all of A, instead of every near pair of nodes.
  template <SphereMode kMode>
  void RunOneSided(std::vector<Entry>* stack, std::vector<NodeRef>* nodes, int pair_level) {
    using S = Spheres<kMode>;
    // Near contact the pair descent finds a pair within a few hundred node
    // tests, far cheaper than descending B to its voxels; it gets a small
    // budget of its own, and only when that runs out does the one-sided
    // descent start (the tests spent are counted, the answer is the same).
    trial_limit_ = res_->node_tests + kTrialBudget;
    Run<kMode>(stack);
    const bool trial_done = !trial_stopped_;
    trial_limit_ = 0;
    if (trial_done || !res_->complete) return;
    // Depth first, B's children nearest A (by the bound on their gap) pushed
    // last, popped first, so that a pair, when there is one, is usually found
    // early. (Best first over all B nodes measured far slower: it expands
    // every shallow node before reaching any voxel. Simple spheres keep the
    // slot order: ordered, a-bite-3shape at +0.5/+0.7 mm took 31k node tests
    // instead of 2-8k, not yet understood.)
    const double limit = 2.0 * grow_sphere_ + kPruneSlackMm;
    nodes->clear();
    const NodeRef root_b = S::Root(b_);
    if (GapToTree<kMode>(b_, root_b, a_) > limit) return;
    nodes->push_back(root_b);
    const NodeRef root_a = S::Root(a_);
    while (!nodes->empty()) {
      const NodeRef n = nodes->back();
      nodes->pop_back();
      if (n.level <= pair_level) {
        stack->clear();
        if (!SpheresOverlap<kMode>(root_a, n)) continue;
        stack->push_back({root_a, n});
        if (!Descend<kMode>(stack) || res_->overlap) return;
        continue;
      }
      NodeRef found[8];
      double gap[8];
      int num_found = 0;
      std::uint32_t child = b_.oct->first_child[n.node];
      for (unsigned mask = b_.oct->child_mask[n.node]; mask != 0; mask &= mask - 1, ++child) {
        const NodeRef c = S::Child(b_, n, child, __builtin_ctz(mask));
        const double g = GapToTree<kMode>(b_, c, a_);
        if (g > limit) continue;
        if (kMode == SphereMode::kSimple) {  // see below
          nodes->push_back(c);
          continue;
        }
        int i = num_found++;
        for (; i > 0 && gap[i - 1] < g; --i) {  // insertion: descending gap
          gap[i] = gap[i - 1];
          found[i] = found[i - 1];
        }
        gap[i] = g;
        found[i] = c;
      }
      for (int i = 0; i < num_found; ++i) nodes->push_back(found[i]);
    }
  }

  /// The boolean with explicit spheres and A's voxel occupancy: B alone is
  /// descended, nearest child first (by the bound's estimate), pruned by A's bound;
  /// a B voxel that survives is tested against the A voxels its grown cube can
  /// reach, read from the bound's finest level, with the exact cube test. Same
  /// answer as Run's pair descent (every B voxel with a pair survives: the
  /// bound is conservative), and the pair it reports is a pair.
  void RunOneSidedExplicit(std::vector<std::pair<std::uint32_t, int>>* stack) {
    const DistanceBound& bound = *a_.bound;
    const double inv = 1.0 / bound.cell_mm();
    const Eigen::Matrix3d A = b_.R * inv;
    const Eigen::Vector3d t = (b_.t - bound.origin()) * inv;
    const double limit = 2.0 * grow_sphere_ + kPruneSlackMm;
    const Eigen::Vector4f* sph = b_.tree->explicit_spheres().compact.data();
    // A node goes on when the bound cannot put its sphere beyond `limit` of
    // A's voxels; the probe's gap estimate orders the survivors.
    auto probe = [&](std::uint32_t n) {
      ++res_->bound_tests;
      return bound.ProbeAt(A * sph[n].head<3>().cast<double>() + t,
                           static_cast<double>(sph[n].w()) + limit);
    };
    stack->clear();
    if (probe(0).excluded) return;
    stack->push_back({0u, b_.oct->top_level});
    const Octree& oct = *b_.oct;
    while (!stack->empty()) {
      const auto [node, level] = stack->back();
      stack->pop_back();
      if (level == 0) {
        if (LeafAgainstOccupancy(node)) return;
        continue;
      }
      // Children with their gaps, pushed farthest first (popped nearest first).
      std::pair<double, std::uint32_t> found[8];
      int num_found = 0;
      const std::uint32_t first = oct.first_child[node];
      for (std::uint32_t child = first + kPopCount8[oct.child_mask[node]]; child-- > first;) {
        const DistanceBound::Probe p = probe(child);
        if (p.excluded) continue;
        const double g = p.gap_estimate;
        int i = num_found++;
        for (; i > 0 && found[i - 1].first < g; --i) found[i] = found[i - 1];  // descending gap
        found[i] = {g, child};
      }
      for (int i = 0; i < num_found; ++i) stack->push_back({found[i].second, level - 1});
    }
  }

 private:
  // The A voxels whose cubes, grown by delta / 2, can meet B voxel `leaf`'s
  // grown cube (the A voxel indices its projections span), from A's bound's
  // occupancy, each with the exact test; true (and the pair recorded) at the
  // first that does.
  bool LeafAgainstOccupancy(std::uint32_t leaf) {
    const DistanceBound& bound = *a_.bound;
    const VoxelGrid& grid = a_.tree->grid();
    const Eigen::Vector3d cb = b_.VoxelCenterA(leaf);
    const double g = 0.5 * req_.delta_mm, h = 0.5 * b_.s, inv = 1.0 / a_.s;
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      const double e = h * b_.R.row(k).cwiseAbs().sum() + 2.0 * g + kPruneSlackMm;
      const double q = (cb[k] - grid.origin_F[k]) * inv;
      if (!(std::abs(q) < 1 << 22)) return false;  // far outside A's grid (also NaN)
      lo[k] = static_cast<int>(std::floor(q - e * inv));
      hi[k] = static_cast<int>(std::floor(q + e * inv));
    }
    for (int z = lo[2]; z <= hi[2]; ++z) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) {
          if (!bound.VoxelOccupied(x, y, z)) continue;
          ++res_->leaf_tests;
          const Eigen::Vector3d ca =
              grid.origin_F + a_.s * (Eigen::Vector3d(x, y, z) + Eigen::Vector3d::Constant(0.5));
          if (!cube_test_.Overlap(cb - ca)) continue;
          const std::uint64_t key = MortonEncode(x, y, z);
          const auto it = std::lower_bound(grid.surface_keys.begin(), grid.surface_keys.end(), key);
          res_->overlap = true;
          res_->pairs.push_back({static_cast<std::uint32_t>(it - grid.surface_keys.begin()),
                                 leaf - b_.oct->leaf_begin()});
          return true;
        }
      }
    }
    return false;
  }

  // Runs the pair descent on `stack`; false when it stopped early (the first
  // pair of a boolean query, or the work budget).
  template <SphereMode kMode>
  bool Descend(std::vector<Entry>* stack) {
    while (!stack->empty()) {
      const Entry e = stack->back();
      stack->pop_back();
      if (e.a.level == 0 && e.b.level == 0) {
        if (LeafPair(e) && req_.first_only) return false;
        continue;
      }
      const bool split_a =
          e.b.level == 0 || (e.a.level > 0 && a_.edge[e.a.level] >= b_.edge[e.b.level]);
      if (split_a) {
        if (!Split<kMode>(a_, e.a, e.b, true, stack)) return false;
      } else {
        if (!Split<kMode>(b_, e.b, e.a, false, stack)) return false;
      }
    }
    return true;
  }

 private:
  template <SphereMode kMode>
  bool SpheresOverlap(const NodeRef& na, const NodeRef& nb) {
    ++res_->node_tests;
    return NodesOverlap<kMode>(a_, b_, na, nb, grow_sphere_);
  }

  // Splits `node` (of `side`) against `other`; returns false when the budget ran out.
  template <SphereMode kMode>
  bool Split(const Side& side, const NodeRef& node, const NodeRef& other, bool node_is_a,
             std::vector<Entry>* stack) {
    const Octree& oct = *side.oct;
    std::uint32_t child = oct.first_child[node.node];
    // Boolean queries push the passing children farthest first, so that the
    // closest pair (the likeliest to hold a voxel pair) is popped next.
    Entry found[8];
    double gap[8];
    int num_found = 0;
    Eigen::Vector3d c_other = Eigen::Vector3d::Zero();
    double r_other = 0.0;
    const bool sorted = req_.first_only;
    if (sorted) Spheres<kMode>::Sphere(node_is_a ? b_ : a_, other, &c_other, &r_other);
    for (unsigned mask = oct.child_mask[node.node]; mask != 0; mask &= mask - 1, ++child) {
      if (req_.max_node_tests != 0 && res_->node_tests >= req_.max_node_tests) {
        res_->complete = false;
        return false;
      }
      if (trial_limit_ != 0 && res_->node_tests >= trial_limit_) {
        trial_stopped_ = true;
        return false;
      }
      const int slot = __builtin_ctz(mask);
      const NodeRef c = Spheres<kMode>::Child(side, node, child, slot);
      const bool hit =
          node_is_a ? SpheresOverlap<kMode>(c, other) : SpheresOverlap<kMode>(other, c);
      if (!hit || FarFromTree<kMode>(side, c, node_is_a ? b_ : a_)) continue;
      if (!sorted) {
        stack->push_back(node_is_a ? Entry{c, other} : Entry{other, c});
        continue;
      }
      Eigen::Vector3d cc = Eigen::Vector3d::Zero();
      double rc = 0.0;
      Spheres<kMode>::Sphere(side, c, &cc, &rc);
      int i = num_found++;
      const double g = (cc - c_other).norm() - rc;
      for (; i > 0 && gap[i - 1] < g; --i) {  // insertion: descending gap
        gap[i] = gap[i - 1];
        found[i] = found[i - 1];
      }
      gap[i] = g;
      found[i] = node_is_a ? Entry{c, other} : Entry{other, c};
    }
    for (int i = 0; i < num_found; ++i) stack->push_back(found[i]);
    return true;
  }

  // The distance-bound test of node n (of `side`) against the whole `tree`: a
  // voxel pair below n needs n's sphere within 2 * grow_sphere of a voxel cube
  // of `tree` (each grown cube lies within grow_sphere of its cube).
  template <SphereMode kMode>
  bool FarFromTree(const Side& side, const NodeRef& n, const Side& tree) {
    if (!req_.distance_bound || tree.bound == nullptr) return false;
    ++res_->bound_tests;
    Eigen::Vector3d c;
    double r = 0.0;
    Spheres<kMode>::Sphere(side, n, &c, &r);
    return tree.Excludes(c, r + 2.0 * grow_sphere_ + kPruneSlackMm);
  }

  // Lower bound of the gap between node n's sphere and `tree`'s voxel cubes
  // (the bound is built: the one-sided descent only runs then).
  template <SphereMode kMode>
  double GapToTree(const Side& side, const NodeRef& n, const Side& tree) {
    ++res_->bound_tests;
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    double r = 0.0;
    Spheres<kMode>::Sphere(side, n, &c, &r);
    return tree.bound->LowerBound(tree.FromA(c)) - r;
  }

  bool LeafPair(const Entry& e) {
    ++res_->leaf_tests;
    const Eigen::Vector3d ca = a_.VoxelCenterA(e.a.node);
    const Eigen::Vector3d cb = b_.VoxelCenterA(e.b.node);
    if (!cube_test_.Overlap(cb - ca)) return false;
    res_->overlap = true;
    res_->pairs.push_back({e.a.node - a_.oct->leaf_begin(), e.b.node - b_.oct->leaf_begin()});
    return true;
  }

  const Side& a_;
  const Side& b_;
  const CollisionRequest& req_;
  CollisionResult* res_;
  double grow_sphere_;
  CubePairTest cube_test_;
  std::size_t trial_limit_ = 0;  // node-test count ending the trial pair descent (0: none)
  bool trial_stopped_ = false;   // the trial pair descent ran out of its budget
};

// One-sided descent for the oracle: B is split only down to `cell_level`, A
// down to its voxels; a (voxel of A, cell of B) pair whose cubes, grown by
// reach/2, overlap marks the cell, and a marked cell is never visited again.
class CellTraversal {
 public:
  CellTraversal(const Side& a, const Side& b, const CellRequest& req, CellResult* res)
      : a_(a), b_(b), req_(req), res_(res), grow_sphere_(kCubeCircumradius * req.reach_mm) {
    for (int level = 0; level <= kMaxCellLevel; ++level) {
      cube_tests_.emplace_back(0.5 * a.s, 0.5 * b.edge[level], b.R, 0.5 * req.reach_mm);
    }
  }

  template <SphereMode kMode>
  void Run(std::vector<Entry>* stack, std::vector<std::uint32_t>* stamps, std::uint32_t gen) {
    using S = Spheres<kMode>;
    stack->clear();
    const Entry root{S::Root(a_), S::Root(b_)};
    ++res_->node_tests;
    if (!NodesOverlap<kMode>(a_, b_, root.a, root.b, grow_sphere_)) return;
    stack->push_back(root);
    const int cell = req_.cell_level;
    while (!stack->empty()) {
      const Entry e = stack->back();
      stack->pop_back();
      const bool b_is_cell = e.b.level <= cell;
      if (b_is_cell && (*stamps)[e.b.node] == gen) continue;
      if (b_is_cell && e.a.level <= req_.a_level && e.a.level > 0) {
        // The node spheres (and slabs) already overlap: a coarse hit.
        (*stamps)[e.b.node] = gen;
        res_->cells_b.push_back(e.b.node);
        continue;
      }
      if (b_is_cell && e.a.level == 0) {
        ++res_->leaf_tests;
        const Eigen::Vector3d cb = b_.ToA(b_.tree->CubeCenter(e.b.node, e.b.level));
        if (cube_tests_[static_cast<std::size_t>(e.b.level)].Overlap(cb -
                                                                     a_.VoxelCenterA(e.a.node))) {
          (*stamps)[e.b.node] = gen;
          res_->cells_b.push_back(e.b.node);
        }
        continue;
      }
      // A is not split below a_level while B still has to reach its cells.
      const int a_floor = b_is_cell ? 0 : req_.a_level;
      const bool split_a =
          e.a.level > a_floor && (b_is_cell || a_.edge[e.a.level] >= b_.edge[e.b.level]);
      const Side& side = split_a ? a_ : b_;
      const NodeRef& node = split_a ? e.a : e.b;
      const NodeRef& other = split_a ? e.b : e.a;
      std::uint32_t child = side.oct->first_child[node.node];
      for (unsigned mask = side.oct->child_mask[node.node]; mask != 0; mask &= mask - 1, ++child) {
        const NodeRef c = Spheres<kMode>::Child(side, node, child, __builtin_ctz(mask));
        ++res_->node_tests;
        const bool hit = split_a ? NodesOverlap<kMode>(a_, b_, c, other, grow_sphere_)
                                 : NodesOverlap<kMode>(a_, b_, other, c, grow_sphere_);
        if (hit) stack->push_back(split_a ? Entry{c, other} : Entry{other, c});
      }
    }
  }

 private:
  const Side& a_;
  const Side& b_;
  const CellRequest& req_;
  CellResult* res_;
  double grow_sphere_;
  std::vector<CubePairTest> cube_tests_;  // per B level 0..kMaxCellLevel
};

// One-sided descent for the oracle with A's distance bound: B alone is split
// down to `cell_level`; a B node is dropped when A's bound proves its sphere
// farther than reach from A's voxel cubes. Each B node is visited at most once,
// so cells need no marks. Stack bound: 1 + 7 * (top_b + 1).
class BoundCellTraversal {
 public:
  BoundCellTraversal(const Side& a, const Side& b, const CellRequest& req, CellResult* res)
      : a_(a), b_(b), req_(req), res_(res) {}

  /// Explicit spheres: each node's stored centre goes straight into the
  /// coordinates of A's bound (one affine map), and the stack holds only node
  /// indices and levels. Same cells, in the same order, as Run<kExplicit>.
  void RunExplicit(std::vector<std::pair<std::uint32_t, int>>* stack) {
    const DistanceBound& bound = *a_.bound;
    const double inv = 1.0 / bound.cell_mm();
    const Eigen::Matrix3d A = b_.R * inv;
    const Eigen::Vector3d t = (b_.t - bound.origin()) * inv;
    const double grow = req_.reach_mm + kPruneSlackMm;
    const Eigen::Vector4f* sph =
        req_.b_spheres != nullptr ? req_.b_spheres : b_.tree->explicit_spheres().compact.data();
    auto centre = [&](std::uint32_t n) {
      return Eigen::Vector3d(A * sph[n].head<3>().cast<double>() + t);
    };
    // A negative radius (nothing to find in the node) fails every exclusion
    // test's margin unless handled: such nodes are dropped untested.
    auto far = [&](std::uint32_t n) {
      if (sph[n].w() < 0.0f) return true;
      ++res_->node_tests;
      return bound.ExcludesAt(centre(n), static_cast<double>(sph[n].w()) + grow);
    };
    stack->clear();
    if (far(0)) return;
    stack->push_back({0u, b_.oct->top_level});
    const Octree& oct = *b_.oct;
    while (!stack->empty()) {
      const auto [node, level] = stack->back();
      stack->pop_back();
      if (level <= req_.cell_level) {
        res_->cells_b.push_back(node);
        continue;
      }
      // All children's bound cells first (their cache misses overlap), then
      // the tests, last child first so that they pop in order.
      const std::uint32_t first = oct.first_child[node];
      const int count = kPopCount8[oct.child_mask[node]];
      Eigen::Vector3d q[8];
      for (int k = 0; k < count; ++k) {
        q[k] = centre(first + static_cast<std::uint32_t>(k));
        bound.Prefetch(q[k],
                       static_cast<double>(sph[first + static_cast<std::uint32_t>(k)].w()) + grow);
      }
      for (int k = count; k-- > 0;) {
        const std::uint32_t child = first + static_cast<std::uint32_t>(k);
        if (sph[child].w() < 0.0f) continue;
        ++res_->node_tests;
        if (!bound.ExcludesAt(q[k], static_cast<double>(sph[child].w()) + grow))
          stack->push_back({child, level - 1});
      }
    }
  }

  template <SphereMode kMode>
  void Run(std::vector<NodeRef>* stack) {
    using S = Spheres<kMode>;
    stack->clear();
    const NodeRef root = S::Root(b_);
    if (Far<kMode>(root)) return;
    stack->push_back(root);
    while (!stack->empty()) {
      const NodeRef n = stack->back();
      stack->pop_back();
      if (n.level <= req_.cell_level) {
        res_->cells_b.push_back(n.node);
        continue;
      }
      // Children pushed last slot first, so that they pop in slot order: the
      // cells come out in ascending node (Morton) order, which keeps the
      // caller's walk through per-cell data and the other tree's space forward.
      const unsigned mask = b_.oct->child_mask[n.node];
      std::uint32_t child = b_.oct->first_child[n.node] + kPopCount8[mask];
      for (unsigned m = mask; m != 0;) {
        const int slot = 31 - __builtin_clz(m);
        m &= ~(1u << slot);
        const NodeRef c = S::Child(b_, n, --child, slot);
        if (!Far<kMode>(c)) stack->push_back(c);
      }
    }
  }

 private:
  template <SphereMode kMode>
  bool Far(const NodeRef& n) {
    ++res_->node_tests;
    Eigen::Vector3d c;
    double r = 0.0;
    Spheres<kMode>::Sphere(b_, n, &c, &r);
    return a_.Excludes(c, r + req_.reach_mm + kPruneSlackMm);
  }

  const Side& a_;
  const Side& b_;
  const CellRequest& req_;
  CellResult* res_;
};

// B level at which the one-sided boolean descent hands a surviving node to the
// pair descent: 0 (voxels) measured fastest on a-bite-3shape (1 and 2 let more
// near-miss pairs of nodes through at +1 mm open).
constexpr int kOneSidedPairLevel = 0;

void ValidatePose(const Eigen::Isometry3d& X_AB) {
  if (!X_AB.matrix().allFinite()) throw std::invalid_argument("X_AB has non-finite entries");
  const Eigen::Matrix3d RtR = X_AB.linear().transpose() * X_AB.linear();
  if (!RtR.isApprox(Eigen::Matrix3d::Identity(), 1e-6) || X_AB.linear().determinant() < 0) {
    throw std::invalid_argument("X_AB is not a rigid transform (rotation not orthonormal)");
  }
}

void Validate(const Eigen::Isometry3d& X_AB, const CollisionRequest& request) {
  if (!(request.delta_mm >= 0.0) || !std::isfinite(request.delta_mm)) {
    throw std::invalid_argument("CollisionRequest.delta_mm must be finite and >= 0");
  }
  ValidatePose(X_AB);
}

}  // namespace

void CollisionResult::Clear() {
  overlap = false;
  complete = true;
  node_tests = leaf_tests = bound_tests = triangle_tests = 0;
  pairs.clear();
  contacts.clear();
  triangles_intersect = false;
  min_distance_mm = std::numeric_limits<double>::infinity();
  closest = TriangleContact{};
}

bool GrownCubesOverlap(const Eigen::Vector3d& c_a, double h_a, const Eigen::Vector3d& c_b,
                       double h_b, const Eigen::Matrix3d& R, double grow) {
  return CubePairTest(h_a, h_b, R, grow).Overlap(c_b - c_a);
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
  if (mode == SphereMode::kExplicit && b.explicit_spheres().empty())
    mode = b.explicit_spheres().from;
  if (mode == SphereMode::kExplicit && a.explicit_spheres().empty())
    mode = a.explicit_spheres().from;
  if (request.first_only && request.distance_bound && side_a.bound != nullptr &&
      mode == SphereMode::kExplicit && side_a.bound->has_voxel_occupancy() &&
      request.max_node_tests == 0) {
    thread_local std::vector<std::pair<std::uint32_t, int>> nodes;
    traversal.RunOneSidedExplicit(&nodes);
  } else if (request.first_only && request.distance_bound && side_a.bound != nullptr) {
    thread_local std::vector<NodeRef> nodes;
    const int pair_level = kOneSidedPairLevel;
    switch (mode) {
      case SphereMode::kSimple:
        traversal.RunOneSided<SphereMode::kSimple>(&stack, &nodes, pair_level);
        break;
      case SphereMode::kOptimized:
        traversal.RunOneSided<SphereMode::kOptimized>(&stack, &nodes, pair_level);
        break;
      case SphereMode::kExplicit:
        traversal.RunOneSided<SphereMode::kExplicit>(&stack, &nodes, pair_level);
        break;
    }
  } else {
    switch (mode) {
      case SphereMode::kSimple:
        traversal.Run<SphereMode::kSimple>(&stack);
        break;
      case SphereMode::kOptimized:
        traversal.Run<SphereMode::kOptimized>(&stack);
        break;
      case SphereMode::kExplicit:
        traversal.Run<SphereMode::kExplicit>(&stack);
        break;
    }
  }
  if (request.exact) RefineExact(a, b, X_AB, request.delta_mm, result);
}

void CollectCells(const SphereTree& a, const SphereTree& b, const Eigen::Isometry3d& X_AB,
                  const CellRequest& request, CellResult* result) {
  if (!(request.reach_mm >= 0.0) || !std::isfinite(request.reach_mm)) {
    throw std::invalid_argument("CellRequest.reach_mm must be finite and >= 0");
  }
  if (request.cell_level < 0 || request.cell_level > kMaxCellLevel) {
    throw std::invalid_argument("CellRequest.cell_level must be in 0..3");
  }
  if (request.a_level < 0 || request.a_level > kMaxLevels - 1) {
    throw std::invalid_argument("CellRequest.a_level must be >= 0");
  }
  ValidatePose(X_AB);
  result->cells_b.clear();
  result->node_tests = result->leaf_tests = 0;
  if (a.empty() || b.empty()) return;
  const DistanceBound& a_bound = request.a_bound != nullptr ? *request.a_bound : a.distance_bound();
  if (request.distance_bound && !a_bound.empty()) {
    thread_local std::vector<NodeRef> nodes;
    Side side_a(a, Eigen::Isometry3d::Identity(), false);
    side_a.bound = &a_bound;
    const Side side_b(b, X_AB, true);
    BoundCellTraversal traversal(side_a, side_b, request, result);
    // Only B's spheres matter here: the caller's, else B's explicit records when present.
    SphereMode mode = request.spheres;
    if (mode == SphereMode::kExplicit && b.explicit_spheres().empty())
      mode = SphereMode::kOptimized;
    if (request.b_spheres != nullptr || mode == SphereMode::kExplicit) {
      thread_local std::vector<std::pair<std::uint32_t, int>> indices;
      traversal.RunExplicit(&indices);
      return;
    }
    switch (mode) {
      case SphereMode::kSimple:
        traversal.Run<SphereMode::kSimple>(&nodes);
        break;
      case SphereMode::kOptimized:
        traversal.Run<SphereMode::kOptimized>(&nodes);
        break;
      case SphereMode::kExplicit:
        traversal.Run<SphereMode::kExplicit>(&nodes);
        break;
    }
    return;
  }
  thread_local std::vector<Entry> stack;
  thread_local std::vector<std::uint32_t> stamps;
  thread_local std::uint32_t generation = 0;
  if (++generation == 0) {  // wrapped: forget every old stamp
    std::fill(stamps.begin(), stamps.end(), 0u);
    generation = 1;
  }
  if (stamps.size() < b.octree().num_nodes()) stamps.resize(b.octree().num_nodes(), 0u);
  const Side side_a(a, Eigen::Isometry3d::Identity(), false);
  const Side side_b(b, X_AB, true);
  CellTraversal traversal(side_a, side_b, request, result);
  SphereMode mode = request.spheres;
  if (mode == SphereMode::kExplicit &&
      (a.explicit_spheres().empty() || b.explicit_spheres().empty())) {
    mode = SphereMode::kOptimized;
  }
  switch (mode) {
    case SphereMode::kSimple:
      traversal.Run<SphereMode::kSimple>(&stack, &stamps, generation);
      break;
    case SphereMode::kOptimized:
      traversal.Run<SphereMode::kOptimized>(&stack, &stamps, generation);
      break;
    case SphereMode::kExplicit:
      traversal.Run<SphereMode::kExplicit>(&stack, &stamps, generation);
      break;
  }
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
