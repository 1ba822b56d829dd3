// Ground truth of the accuracy study (see bench_accuracy_truth_internal.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "bench/bench_accuracy_truth_internal.h"
#include "occlude/collision/closest_point.h"

namespace occlude::app {

// ---- LowerDistance ----------------------------------------------------------

LowerDistance::Cell LowerDistance::CellOf(const Eigen::Vector3d& p, double size) const {
  const Eigen::Vector3d q = (p - origin_) / size;
  return Cell(static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y())),
              static_cast<int>(std::floor(q.z())));
}

// Cells of edge `size` over the bounds, grown until at most kMaxCells (memory).
LowerDistance::Grid LowerDistance::MakeGrid(double size) const {
  constexpr double kMaxCells = 32e6;
  Grid g;
  g.size = size;
  for (;;) {
    const Eigen::Vector3d n = (bounds_.sizes() / g.size).array().floor() + 1.0;
    if (n.prod() <= kMaxCells) {
      g.dims = n.cast<int>();
      return g;
    }
    g.size *= 1.01 * std::cbrt(n.prod() / kMaxCells);
  }
}

LowerDistance::LowerDistance(std::shared_ptr<const io::TriangleMesh> lower_L, double cell_mm)
    : mesh_(std::move(lower_L)) {
  if (!mesh_ || mesh_->empty()) throw std::invalid_argument("LowerDistance: empty lower mesh");
  if (!(cell_mm >= 0.0)) throw std::invalid_argument("LowerDistance: cell_mm must be >= 0");
  const io::TriangleMesh& m = *mesh_;
  if (cell_mm == 0.0) {
    std::vector<double> edges;
    for (std::size_t t = 0; t < m.num_triangles(); ++t) {
      const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
      edges.push_back(std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()}));
    }
    std::nth_element(edges.begin(), edges.begin() + static_cast<long>(edges.size() / 2),
                     edges.end());
    cell_mm = std::clamp(edges[edges.size() / 2], 0.25, 5.0);
  }
  normals_ = collision::PseudoNormals(m);
  bounds_ = m.Bounds();
  origin_ = bounds_.min();
  fine_ = MakeGrid(cell_mm);
  coarse_ = MakeGrid(4.0 * fine_.size);
  // Counting sort of (cell, triangle) over the cells each triangle's box overlaps.
  std::vector<std::pair<Cell, Cell>> boxes(m.num_triangles());
  cell_begin_.assign(fine_.count() + 1, 0);
  coarse_occupied_.assign(coarse_.count(), 0);
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    Eigen::AlignedBox3d box;
    for (int k = 0; k < 3; ++k) box.extend(m.corner(t, k));
    boxes[t] = {CellOf(box.min(), fine_.size).cwiseMax(0).cwiseMin(fine_.dims - Cell::Ones()),
                CellOf(box.max(), fine_.size).cwiseMax(0).cwiseMin(fine_.dims - Cell::Ones())};
    for (int z = boxes[t].first.z(); z <= boxes[t].second.z(); ++z)
      for (int y = boxes[t].first.y(); y <= boxes[t].second.y(); ++y)
        for (int x = boxes[t].first.x(); x <= boxes[t].second.x(); ++x)
          ++cell_begin_[static_cast<std::size_t>(fine_.Index(Cell(x, y, z))) + 1];
    const Cell lo = CellOf(box.min(), coarse_.size), hi = CellOf(box.max(), coarse_.size);
    for (int z = lo.z(); z <= hi.z(); ++z)
      for (int y = lo.y(); y <= hi.y(); ++y)
        for (int x = lo.x(); x <= hi.x(); ++x) {
          const long i = coarse_.Index(Cell(x, y, z));
          if (i >= 0) coarse_occupied_[static_cast<std::size_t>(i)] = 1;
        }
  }
  for (std::size_t i = 1; i < cell_begin_.size(); ++i) cell_begin_[i] += cell_begin_[i - 1];
  cell_triangles_.resize(cell_begin_.back());
  std::vector<std::uint32_t> fill(cell_begin_.begin(), cell_begin_.end() - 1);
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    for (int z = boxes[t].first.z(); z <= boxes[t].second.z(); ++z)
      for (int y = boxes[t].first.y(); y <= boxes[t].second.y(); ++y)
        for (int x = boxes[t].first.x(); x <= boxes[t].second.x(); ++x)
          cell_triangles_[fill[static_cast<std::size_t>(fine_.Index(Cell(x, y, z)))]++] =
              static_cast<std::uint32_t>(t);
  }
  seen_.assign(m.num_triangles(), 0);
}

void LowerDistance::Visit(const Cell& c, const Eigen::Vector3d& p, double* best2,
                          std::uint32_t* best_t, Eigen::Vector3d* best_bary) const {
  const long index = fine_.Index(c);
  if (index < 0) return;
  const auto i0 = cell_begin_[static_cast<std::size_t>(index)];
  const auto i1 = cell_begin_[static_cast<std::size_t>(index) + 1];
  for (std::uint32_t i = i0; i < i1; ++i) {
    const std::uint32_t t = cell_triangles_[i];
    if (seen_[t] == epoch_) continue;
    seen_[t] = epoch_;
    const collision::TrianglePoint q = collision::ClosestPointOnTriangle(
        p, mesh_->corner(t, 0), mesh_->corner(t, 1), mesh_->corner(t, 2));
    if (q.squared_distance < *best2) {
      *best2 = q.squared_distance;
      *best_t = t;
      *best_bary = q.barycentric;
    }
  }
}

bool LowerDistance::Signed(const Eigen::Vector3d& p_L, double max_mm, double* d) const {
  if (++epoch_ == 0) {  // wrapped: clear the marks
    std::fill(seen_.begin(), seen_.end(), 0);
    epoch_ = 1;
  }
  const double cell = fine_.size;
  const Cell c = CellOf(p_L, cell);
  double best2 = std::numeric_limits<double>::infinity();
  std::uint32_t best_t = 0;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
  const int max_ring = static_cast<int>(std::ceil(max_mm / cell)) + 1;
  for (int k = 0; k <= max_ring; ++k) {
    for (int z = -k; z <= k; ++z) {
      for (int y = -k; y <= k; ++y) {
        const bool face = std::abs(z) == k || std::abs(y) == k;
        for (int x = -k; x <= k; x += (face ? 1 : 2 * std::max(k, 1))) {
          Visit(c + Cell(x, y, z), p_L, &best2, &best_t, &bary);
        }
      }
    }
    // Every point outside the box of cells visited so far is at least `clear`
    // from p, so a triangle not yet seen is at least that far.
    const Eigen::Vector3d lo = origin_ + cell * (c - Cell::Constant(k)).cast<double>();
    const Eigen::Vector3d hi = origin_ + cell * (c + Cell::Constant(k + 1)).cast<double>();
    const double clear = std::min((p_L - lo).minCoeff(), (hi - p_L).minCoeff());
    if (best2 <= clear * clear) break;
    if (clear > max_mm) break;
  }
  if (!(best2 <= max_mm * max_mm)) return false;
  const collision::TrianglePoint q = collision::ClosestPointOnTriangle(
      p_L, mesh_->corner(best_t, 0), mesh_->corner(best_t, 1), mesh_->corner(best_t, 2));
  // The oracle's sign rule (PseudoNormals::Signed): a point whose closest point lies on
  // an open border counts as outside.
  *d = normals_.Signed(best_t, bary, p_L, q.point, nullptr);
  return true;
}

bool LowerDistance::MayBeWithin(const Eigen::Vector3d& p_L, double max_mm) const {
  if (bounds_.exteriorDistance(p_L) > max_mm) return false;
  const Cell lo = CellOf(p_L - Eigen::Vector3d::Constant(max_mm), coarse_.size)
                      .cwiseMax(0)
                      .cwiseMin(coarse_.dims - Cell::Ones());
  const Cell hi = CellOf(p_L + Eigen::Vector3d::Constant(max_mm), coarse_.size)
                      .cwiseMax(0)
                      .cwiseMin(coarse_.dims - Cell::Ones());
  for (int z = lo.z(); z <= hi.z(); ++z)
    for (int y = lo.y(); y <= hi.y(); ++y)
      for (int x = lo.x(); x <= hi.x(); ++x)
        if (coarse_occupied_[static_cast<std::size_t>(coarse_.Index(Cell(x, y, z)))]) return true;
  return false;
}

// ---- UpperSamples -----------------------------------------------------------

UpperSamples::UpperSamples(std::shared_ptr<const io::TriangleMesh> upper_U, double spacing_mm)
    : mesh_(std::move(upper_U)), spacing_(spacing_mm) {
  if (!mesh_ || mesh_->empty()) throw std::invalid_argument("UpperSamples: empty upper mesh");
  if (!(spacing_mm > 0.0)) throw std::invalid_argument("UpperSamples: spacing must be > 0");
  const io::TriangleMesh& m = *mesh_;
  const std::size_t n = m.num_triangles();
  std::vector<bool> vertex_owned(m.num_vertices(), false);
  begin_.assign(n + 1, 0);
  pieces_.resize(n);
  owned_mask_.assign(n, 0);
  centre_U_.resize(n);
  radius_.resize(n);
  std::uint64_t total = 0;
  for (std::size_t t = 0; t < n; ++t) {
    const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const double k = std::clamp(std::ceil(longest / spacing_), 1.0, 65535.0);
    pieces_[t] = static_cast<std::uint16_t>(k);
    std::uint64_t count = static_cast<std::uint64_t>(k) * static_cast<std::uint64_t>(k);
    for (int corner = 0; corner < 3; ++corner) {
      const auto v = static_cast<std::size_t>(m.triangles[t][corner]);
      if (!vertex_owned[v]) {
        vertex_owned[v] = true;
        owned_mask_[t] |= static_cast<std::uint8_t>(1u << corner);
        ++count;
      }
    }
    begin_[t] = static_cast<std::uint32_t>(total);
    total += count;
    if (total > std::numeric_limits<std::uint32_t>::max()) {
      throw std::invalid_argument("UpperSamples: more than 2^32 samples (raise the spacing)");
    }
    centre_U_[t] = (a + b + c) / 3.0;
    radius_[t] =
        std::max({(a - centre_U_[t]).norm(), (b - centre_U_[t]).norm(), (c - centre_U_[t]).norm()});
  }
  begin_[n] = static_cast<std::uint32_t>(total);
}

void UpperSamples::Generate(std::size_t t, std::vector<Eigen::Vector3d>* p_U) const {
  p_U->clear();
  const io::TriangleMesh& m = *mesh_;
  const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
  const int k = pieces_[t];
  const Eigen::Vector3d u = (b - a) / k, v = (c - a) / k;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; i + j < k; ++j) {
      const Eigen::Vector3d o = a + i * u + j * v;
      p_U->push_back(o + (u + v) / 3.0);
      if (i + j < k - 1) p_U->push_back(o + 2.0 * (u + v) / 3.0);
    }
  }
  for (int corner = 0; corner < 3; ++corner) {
    if (owned_mask_[t] & (1u << corner)) p_U->push_back(m.corner(t, corner));
  }
}

std::uint32_t UpperSamples::TriangleOf(std::uint32_t id) const {
  const auto it = std::upper_bound(begin_.begin(), begin_.end(), id);
  return static_cast<std::uint32_t>(it - begin_.begin() - 1);
}

}  // namespace occlude::app
