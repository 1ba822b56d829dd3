// Interior stage of Voxelize.
//
// 1. Connected components of triangles (union-find over triangles joined across
//    manifold edges, see FindComponents). A component is closed when each
//    undirected edge of its non-degenerate triangles is used exactly twice by
//    the component; open components never get an interior.
// 2. For each closed component, each triangle is intersected with the +x lines
//    through the voxel centres of the (y, z) rows its projection covers (so the
//    cost is triangles x rows they cover, never the bounding volume). The
//    crossings of one row, sorted by x, pair up into inside intervals (even-odd
//    rule, per component, so overlapping components unite rather than cancel).
// 3. Intervals of all components are merged per row, cut into voxel runs (voxels
//    whose centres lie strictly inside), and surface voxels are cut out.
//
// Robustness of the row/triangle test: it uses 2-D edge functions in the (y, z)
// plane, each evaluated with the edge's endpoints in a canonical order (by (y, z))
// so that the two triangles sharing an edge compute bit-identical values of
// opposite sign. A row that passes exactly through an edge or vertex is resolved
// by simulation of simplicity: the row is treated as if moved by (eps, eps^2) in
// (y, z), which decides a zero edge function from the edge direction alone. Each
// crossing of a watertight surface is thus counted exactly once, and a row
// grazing a silhouette is counted twice or not at all, keeping parity right.
#include <cmath>

#include "occlude/collision/morton.h"
#include "voxelize_detail.h"

namespace occlude::collision::detail {
namespace {

struct Components {
  std::vector<std::int32_t> of_triangle;  // dense component id per triangle
  std::vector<std::uint8_t> closed;       // per component
};

std::int32_t FindRoot(std::vector<std::int32_t>& parent, std::int32_t v) {
  while (parent[static_cast<std::size_t>(v)] != v) {
    auto& p = parent[static_cast<std::size_t>(v)];
    p = parent[static_cast<std::size_t>(p)];  // path halving
    v = p;
  }
  return v;
}

void Unite(std::vector<std::int32_t>& parent, std::int32_t a, std::int32_t b) {
  a = FindRoot(parent, a);
  b = FindRoot(parent, b);
  if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
}

bool IndexDegenerate(const Eigen::Vector3i& tri) {
  return tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0];
}

/// An undirected edge (smaller vertex in the high bits) and a triangle using it.
struct EdgeUse {
  std::uint64_t edge;
  std::uint32_t tri;
};

/// Edge uses of the non-degenerate triangles, sorted by edge (then triangle).
std::vector<EdgeUse> SortedEdgeUses(const io::TriangleMesh& mesh, int* edge_bits) {
  const int vb = std::max(1, BitWidth(mesh.num_vertices() - 1));
  *edge_bits = 2 * vb;
  std::vector<EdgeUse> uses;
  uses.reserve(3 * mesh.num_triangles());
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    if (IndexDegenerate(tri)) continue;
    for (int e = 0; e < 3; ++e) {
      const auto a = static_cast<std::uint64_t>(tri[e]);
      const auto b = static_cast<std::uint64_t>(tri[(e + 1) % 3]);
      uses.push_back({std::min(a, b) << vb | std::max(a, b), static_cast<std::uint32_t>(t)});
    }
  }
  std::vector<EdgeUse> scratch;
  RadixSort(
      uses, scratch, [](const EdgeUse& u) { return u.edge; }, 0, *edge_bits);
  return uses;
}

/// Calls f(piece, uses of the edge by that piece) once per distinct piece among
/// the triangles of the edge group [n, m).
template <class F>
void ForEachPieceCount(const std::vector<EdgeUse>& uses, std::size_t n, std::size_t m,
                       const std::vector<std::int32_t>& piece, F f) {
  for (std::size_t a = n; a < m; ++a) {
    const std::int32_t p = piece[uses[a].tri];
    bool first = true;
    std::size_t count = 0;
    for (std::size_t b = n; b < m; ++b) {
      if (piece[uses[b].tri] != p) continue;
      first = first && b >= a;
      ++count;
    }
    if (first) f(p, count);
  }
}

/// End of the edge group starting at n.
std::size_t GroupEnd(const std::vector<EdgeUse>& uses, std::size_t n) {
  std::size_t m = n + 1;
  while (m < uses.size() && uses[m].edge == uses[n].edge) ++m;
  return m;
}

/// Dense labels (numbered by first triangle) of the union-find roots.
std::vector<std::int32_t> Label(std::vector<std::int32_t>& parent, std::int32_t* count) {
  std::vector<std::int32_t> id(parent.size(), -1), label(parent.size());
  *count = 0;
  for (std::size_t t = 0; t < parent.size(); ++t) {
    auto& slot = id[static_cast<std::size_t>(FindRoot(parent, static_cast<std::int32_t>(t)))];
    if (slot < 0) slot = (*count)++;
    label[t] = slot;
  }
  return label;
}

/// Joins pairs of open pieces whose union is closed: P and Q are joined when
/// every edge that P or Q does not use exactly twice is used once by each.
void JoinComplementaryPieces(const std::vector<EdgeUse>& uses,
                             const std::vector<std::int32_t>& piece, std::int32_t num_pieces,
                             std::vector<std::int32_t>* parent) {
  std::vector<std::int32_t> first_tri(static_cast<std::size_t>(num_pieces), -1);
  for (std::size_t t = piece.size(); t-- > 0;) {
    first_tri[static_cast<std::size_t>(piece[t])] = static_cast<std::int32_t>(t);
  }
  std::vector<std::uint32_t> open_edges(static_cast<std::size_t>(num_pieces), 0);
  std::vector<std::uint64_t> votes;  // (P << 32 | Q), P < Q, one per edge both use once
  std::vector<std::int32_t> ones;
  for (std::size_t n = 0, m = 0; n < uses.size(); n = m) {
    m = GroupEnd(uses, n);
    ones.clear();
    ForEachPieceCount(uses, n, m, piece, [&](std::int32_t p, std::size_t count) {
      if (count != 2) ++open_edges[static_cast<std::size_t>(p)];
      if (count == 1) ones.push_back(p);
    });
    for (std::size_t a = 0; a < ones.size(); ++a) {
      for (std::size_t b = a + 1; b < ones.size(); ++b) {
        const auto lo = static_cast<std::uint64_t>(std::min(ones[a], ones[b]));
        const auto hi = static_cast<std::uint64_t>(std::max(ones[a], ones[b]));
        votes.push_back(lo << 32 | hi);
      }
    }
  }
  std::sort(votes.begin(), votes.end());
  for (std::size_t n = 0, m = 0; n < votes.size(); n = m) {
    for (m = n + 1; m < votes.size() && votes[m] == votes[n];) ++m;
    const auto p = static_cast<std::size_t>(votes[n] >> 32);
    const auto q = static_cast<std::size_t>(votes[n] & 0xffffffffu);
    if (open_edges[p] == m - n && open_edges[q] == m - n) {
      Unite(*parent, first_tri[p], first_tri[q]);
    }
  }
}

/// Components of triangles, numbered by first triangle. Triangles are first
/// joined across edges used by exactly two triangles (pieces); then two open
/// pieces are joined when their union is closed (JoinComplementaryPieces). A
/// component is closed when each edge of its triangles is used exactly twice by
/// the component's own triangles. Joining by edges rather than by shared
/// vertices separates shells that touch: in a 3Shape export each tooth is a
/// closed shell (crown plus cap) whose rim is also a rim of the open gingiva, so
/// the rim edges have 3 uses; crown and cap are rejoined into one closed tooth
/// and the gingiva stays open. For a mesh whose every edge is used twice this
/// gives the same interior as joining by shared vertices.
Components FindComponents(const io::TriangleMesh& mesh) {
  int edge_bits = 0;
  const std::vector<EdgeUse> uses = SortedEdgeUses(mesh, &edge_bits);
  std::vector<std::int32_t> parent(mesh.num_triangles());
  for (std::size_t t = 0; t < parent.size(); ++t) parent[t] = static_cast<std::int32_t>(t);
  for (std::size_t n = 0, m = 0; n < uses.size(); n = m) {
    m = GroupEnd(uses, n);
    if (m - n == 2) {
      Unite(parent, static_cast<std::int32_t>(uses[n].tri),
            static_cast<std::int32_t>(uses[n + 1].tri));
    }
  }
  std::int32_t num_pieces = 0;
  const std::vector<std::int32_t> piece = Label(parent, &num_pieces);
  JoinComplementaryPieces(uses, piece, num_pieces, &parent);

  Components c;
  std::int32_t count = 0;
  c.of_triangle = Label(parent, &count);
  // 0 = no edge seen (degenerate triangles only), 1 = closed so far, 2 = open.
  std::vector<std::uint8_t> state(static_cast<std::size_t>(count), 0);
  for (std::size_t n = 0, m = 0; n < uses.size(); n = m) {
    m = GroupEnd(uses, n);
    ForEachPieceCount(uses, n, m, c.of_triangle, [&](std::int32_t comp, std::size_t k) {
      auto& st = state[static_cast<std::size_t>(comp)];
      st = (k == 2 && st != 2) ? 1 : 2;
    });
  }
  c.closed.resize(state.size());
  for (std::size_t k = 0; k < state.size(); ++k) c.closed[k] = state[k] == 1;
  return c;
}

/// Triangles of each component: ids[begin[c] .. begin[c + 1]) (counting sort, ascending).
void GroupByComponent(const Components& c, std::vector<std::uint32_t>* begin,
                      std::vector<std::uint32_t>* ids) {
  begin->assign(c.closed.size() + 1, 0);
  for (const std::int32_t comp : c.of_triangle) ++(*begin)[static_cast<std::size_t>(comp) + 1];
  for (std::size_t n = 1; n < begin->size(); ++n) (*begin)[n] += (*begin)[n - 1];
  ids->resize(c.of_triangle.size());
  std::vector<std::uint32_t> next(begin->begin(), begin->end() - 1);
  for (std::size_t t = 0; t < c.of_triangle.size(); ++t) {
    (*ids)[next[static_cast<std::size_t>(c.of_triangle[t])]++] = static_cast<std::uint32_t>(t);
  }
}

/// Sign of the edge function of the row point (py, pz) against the canonical edge
/// a -> b ((a.y, a.z) < (b.y, b.z)), with the simulation-of-simplicity tie-break.
int CanonicalSign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double py, double pz,
                  double* value) {
  const double e = (a.y() - py) * (b.z() - pz) - (a.z() - pz) * (b.y() - py);
  *value = e;
  if (e > 0.0) return 1;
  if (e < 0.0) return -1;
  // e(p + (eps, eps^2)) = (a.z - b.z) eps + (b.y - a.y) eps^2.
  if (a.z() != b.z()) return a.z() > b.z() ? 1 : -1;
  return b.y() > a.y() ? 1 : -1;
}

/// Where the +x line through (py, pz) crosses triangle p (perturbed as above);
/// false when it misses or the triangle's (y, z) projection has a zero-length edge.
bool RowCrossing(const std::array<Eigen::Vector3d, 3>& p, double py, double pz, double* x) {
  double w[3];
  int sign[3];
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d& u = p[static_cast<std::size_t>(e)];
    const Eigen::Vector3d& v = p[static_cast<std::size_t>((e + 1) % 3)];
    if (u.y() == v.y() && u.z() == v.z()) return false;
    const bool forward = u.y() < v.y() || (u.y() == v.y() && u.z() < v.z());
    double value = 0.0;
    const int sg =
        forward ? CanonicalSign(u, v, py, pz, &value) : CanonicalSign(v, u, py, pz, &value);
    w[e] = forward ? value : -value;
    sign[e] = forward ? sg : -sg;
  }
  if (sign[0] != sign[1] || sign[1] != sign[2]) return false;
  // Barycentric weights: w[1] (edge bc) for a, w[2] (edge ca) for b, w[0] (edge ab) for c.
  *x = (w[1] * p[0].x() + w[2] * p[1].x() + w[0] * p[2].x()) / (w[0] + w[1] + w[2]);
  return true;
}

/// Index range of rows (along y or z) whose voxel centres can lie in [min, max].
void RowRange(const GridFrame& f, int axis, double min, double max, std::int32_t* lo,
              std::int32_t* hi) {
  constexpr double kSlack = 1e-9;
  const double a = std::ceil((min - f.origin[axis]) / f.s - 0.5 - kSlack);
  const double b = std::floor((max - f.origin[axis]) / f.s - 0.5 + kSlack);
  const double top = static_cast<double>(f.dims[axis] - 1);
  *lo = static_cast<std::int32_t>(std::clamp(a, 0.0, top + 1.0));
  *hi = static_cast<std::int32_t>(std::clamp(b, -1.0, top));
}

struct Crossing {
  std::uint64_t row;  // k << coord_bits | j
  double x;
};

struct Interval {
  std::uint64_t row;
  std::int32_t begin;  // voxel x range [begin, end)
  std::int32_t end;
};

/// Appends the crossings of triangle t with every row its projection covers.
void TriangleCrossings(const io::TriangleMesh& mesh, const GridFrame& f, std::uint32_t t,
                       std::vector<Crossing>* out) {
  if (IndexDegenerate(mesh.triangles[t])) return;
  const auto p = Corners(mesh, t);
  std::int32_t lo[3], hi[3];
  for (int axis = 1; axis < 3; ++axis) {
    const double mn = std::min(p[0][axis], std::min(p[1][axis], p[2][axis]));
    const double mx = std::max(p[0][axis], std::max(p[1][axis], p[2][axis]));
    RowRange(f, axis, mn, mx, &lo[axis], &hi[axis]);
  }
  for (std::int32_t k = lo[2]; k <= hi[2]; ++k) {
    const double pz = f.Center(2, k);
    for (std::int32_t j = lo[1]; j <= hi[1]; ++j) {
      double x = 0.0;
      if (RowCrossing(p, f.Center(1, j), pz, &x)) {
        out->push_back(
            {static_cast<std::uint64_t>(k) << f.coord_bits | static_cast<std::uint64_t>(j), x});
      }
    }
  }
}

/// Smallest voxel index i in [0, dims.x] with pred(centre x of i) (pred monotone).
template <class Pred>
std::int32_t FirstVoxel(const GridFrame& f, double x, Pred pred) {
  const double guess = std::ceil((x - f.origin.x()) / f.s - 0.5);
  auto i = static_cast<std::int32_t>(std::clamp(guess, 0.0, static_cast<double>(f.dims.x())));
  while (i > 0 && pred(f.Center(0, i - 1))) --i;
  while (i < f.dims.x() && !pred(f.Center(0, i))) ++i;
  return i;
}

/// Inside intervals of one closed component from its crossings (sorted here);
/// rows with an odd number of crossings are skipped and counted.
void ComponentIntervals(const GridFrame& f, std::vector<Crossing>* crossings,
                        std::vector<Interval>* out, std::size_t* odd_rows) {
  std::sort(crossings->begin(), crossings->end(), [](const Crossing& a, const Crossing& b) {
    return a.row != b.row ? a.row < b.row : a.x < b.x;
  });
  for (std::size_t n = 0; n < crossings->size();) {
    std::size_t m = n;
    while (m < crossings->size() && (*crossings)[m].row == (*crossings)[n].row) ++m;
    if ((m - n) % 2 != 0) {
      ++*odd_rows;
      n = m;
      continue;
    }
    for (; n < m; n += 2) {
      const double x0 = (*crossings)[n].x, x1 = (*crossings)[n + 1].x;
      const std::int32_t b = FirstVoxel(f, x0, [x0](double c) { return c > x0; });
      const std::int32_t e = FirstVoxel(f, x1, [x1](double c) { return c >= x1; });
      if (b < e) out->push_back({(*crossings)[n].row, b, e});
    }
  }
}

/// Morton keys as row-major keys k << 2b | j << b | i (b = coord_bits), sorted.
std::vector<std::uint64_t> RowMajor(const std::vector<std::uint64_t>& morton, const GridFrame& f) {
  const int b = f.coord_bits;
  std::vector<std::uint64_t> keys(morton.size());
  for (std::size_t n = 0; n < keys.size(); ++n) {
    const Eigen::Vector3i q = MortonDecode(morton[n]);
    keys[n] = static_cast<std::uint64_t>(q.z()) << (2 * b) |
              static_cast<std::uint64_t>(q.y()) << b | static_cast<std::uint64_t>(q.x());
  }
  std::vector<std::uint64_t> scratch;
  RadixSort(
      keys, scratch, [](std::uint64_t k) { return k; }, 0, 3 * b);
  return keys;
}

/// Merges intervals per row and cuts out surface voxels, giving the interior runs.
std::vector<VoxelRun> MakeRuns(const GridFrame& f, const VoxelGrid& grid,
                               std::vector<Interval>* intervals) {
  std::sort(intervals->begin(), intervals->end(), [](const Interval& a, const Interval& b) {
    return a.row != b.row ? a.row < b.row : a.begin < b.begin;
  });
  const std::vector<std::uint64_t> surface = RowMajor(grid.surface_keys, f);
  const int b = f.coord_bits;
  const std::uint64_t mask = (std::uint64_t{1} << b) - 1;
  std::vector<VoxelRun> runs;
  std::size_t s = 0;
  auto emit = [&](std::uint64_t row, std::int32_t x0, std::int32_t x1) {
    if (x0 < x1) {
      runs.push_back(
          {static_cast<std::int32_t>(row & mask), static_cast<std::int32_t>(row >> b), x0, x1});
    }
  };
  for (std::size_t n = 0; n < intervals->size();) {
    const Interval first = (*intervals)[n];
    std::int32_t end = first.end;
    for (++n;
         n < intervals->size() && (*intervals)[n].row == first.row && (*intervals)[n].begin <= end;
         ++n) {
      end = std::max(end, (*intervals)[n].end);
    }
    const std::uint64_t base = first.row << b;
    while (s < surface.size() && surface[s] < (base | static_cast<std::uint64_t>(first.begin))) ++s;
    std::int32_t cur = first.begin;
    for (; s < surface.size() && surface[s] < (base | static_cast<std::uint64_t>(end)); ++s) {
      const auto x = static_cast<std::int32_t>(surface[s] & mask);
      emit(first.row, cur, x);
      cur = x + 1;
    }
    emit(first.row, cur, end);
  }
  return runs;
}

/// Removes voxels inside interior runs (sorted, disjoint) from the proximity keys:
/// both are walked in row-major order, so the cost is linear after one sort.
void RemoveInteriorFromProximity(const GridFrame& f, const std::vector<VoxelRun>& runs,
                                 VoxelGrid* grid) {
  if (runs.empty() || grid->proximity_keys.empty()) return;
  const int b = f.coord_bits;
  const std::vector<std::uint64_t> rows = RowMajor(grid->proximity_keys, f);
  std::vector<std::uint64_t> inside;
  std::size_t r = 0;
  for (const std::uint64_t key : rows) {
    auto run_end = [&](const VoxelRun& run) {
      return (static_cast<std::uint64_t>(run.z) << (2 * b) | static_cast<std::uint64_t>(run.y)
                                                                 << b) +
             static_cast<std::uint64_t>(run.x_end);
    };
    while (r < runs.size() && run_end(runs[r]) <= key) ++r;
    if (r == runs.size()) break;
    const std::uint64_t begin =
        run_end(runs[r]) - static_cast<std::uint64_t>(runs[r].x_end - runs[r].x_begin);
    if (key >= begin) {
      const std::uint64_t mask = (std::uint64_t{1} << b) - 1;
      inside.push_back(MortonEncode(static_cast<std::int32_t>(key & mask),
                                    static_cast<std::int32_t>(key >> b & mask),
                                    static_cast<std::int32_t>(key >> (2 * b))));
    }
  }
  if (inside.empty()) return;
  SortUnique(inside, f.key_bits());
  grid->proximity_keys = SortedDifference(grid->proximity_keys, inside);
}

}  // namespace

bool RunsContain(const std::vector<VoxelRun>& runs, std::int32_t x, std::int32_t y,
                 std::int32_t z) {
  // First run that starts after (z, y, x); the candidate is the one before it.
  const auto it = std::upper_bound(runs.begin(), runs.end(), std::array<std::int32_t, 3>{z, y, x},
                                   [](const std::array<std::int32_t, 3>& q, const VoxelRun& r) {
                                     if (q[0] != r.z) return q[0] < r.z;
                                     if (q[1] != r.y) return q[1] < r.y;
                                     return q[2] < r.x_begin;
                                   });
  if (it == runs.begin()) return false;
  const VoxelRun& r = *(it - 1);
  return r.z == z && r.y == y && x < r.x_end;
}

std::vector<std::int32_t> ClosedComponentOfTriangle(const io::TriangleMesh& mesh) {
  const Components c = FindComponents(mesh);
  std::vector<std::int32_t> closed(c.of_triangle.size(), -1);
  for (std::size_t t = 0; t < closed.size(); ++t) {
    if (c.closed[static_cast<std::size_t>(c.of_triangle[t])]) closed[t] = c.of_triangle[t];
  }
  return closed;
}

std::vector<std::int32_t> ComponentOfTriangle(const io::TriangleMesh& mesh) {
  return FindComponents(mesh).of_triangle;
}

void BuildInterior(const io::TriangleMesh& mesh, const GridFrame& frame, VoxelGrid* grid,
                   VoxelizeStats* stats) {
  const Components comps = FindComponents(mesh);
  std::vector<std::uint32_t> begin, ids;
  GroupByComponent(comps, &begin, &ids);
  std::vector<Interval> intervals;
  std::vector<Crossing> crossings;
  for (std::size_t c = 0; c < comps.closed.size(); ++c) {
    if (!comps.closed[c]) {
      ++stats->open_components;
      continue;
    }
    ++stats->closed_components;
    crossings.clear();
    for (std::uint32_t n = begin[c]; n < begin[c + 1]; ++n) {
      TriangleCrossings(mesh, frame, ids[n], &crossings);
    }
    ComponentIntervals(frame, &crossings, &intervals, &stats->interior_odd_rows);
  }
  std::vector<VoxelRun> runs = MakeRuns(frame, *grid, &intervals);
  RemoveInteriorFromProximity(frame, runs, grid);
  grid->interior_runs = std::move(runs);
  grid->interior_runs.shrink_to_fit();
}

}  // namespace occlude::collision::detail
