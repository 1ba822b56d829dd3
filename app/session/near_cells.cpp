// The near cells of a mesh (see near_cells.h).
#include "session/near_cells.h"

#include <cmath>
#include <limits>

namespace occlude::app {
namespace {

// Bitmaps above this many cells give way to the hash set (64 MiB).
constexpr std::int64_t kMaxBitmapCells = std::int64_t{1} << 26;

std::uint64_t CellKey(const Eigen::Vector3i& c) {
  auto u = [](int v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff; };
  return (u(c.x()) << 42) | (u(c.y()) << 21) | u(c.z());
}

Eigen::Vector3i CellOf(const Eigen::Vector3d& p, double cell) {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / cell)),
                         static_cast<int>(std::floor(p.y() / cell)),
                         static_cast<int>(std::floor(p.z() / cell)));
}

template <typename Visit>
void ForCells(const Eigen::Vector3i& l, const Eigen::Vector3i& h, Visit&& visit) {
  for (int x = l.x(); x <= h.x(); ++x) {
    for (int y = l.y(); y <= h.y(); ++y) {
      for (int z = l.z(); z <= h.z(); ++z) visit(Eigen::Vector3i(x, y, z));
    }
  }
}

}  // namespace

NearCells::NearCells(const io::TriangleMesh& mesh, double reach_mm) : reach_mm_(reach_mm) {
  Eigen::Vector3i hi;
  grow_ = 2;
  cell_ = reach_mm * (1.0 + 1e-9) / grow_;
  std::vector<Box> boxes = Boxes(mesh, &hi);
  if (boxes.empty()) return;
  lo_ -= Eigen::Vector3i::Constant(grow_);  // room for the dilation
  dims_ = (hi - lo_ + Eigen::Vector3i::Constant(1 + grow_)).cast<std::int64_t>();
  if (dims_.prod() > kMaxBitmapCells) {
    grow_ = 1;
    cell_ = reach_mm * (1.0 + 1e-9);
    boxes = Boxes(mesh, &hi);
    const Eigen::Vector3i g = Eigen::Vector3i::Constant(grow_);
    for (const auto& [l, h] : boxes)
      ForCells(l - g, h + g, [&](const Eigen::Vector3i& c) { set_.insert(CellKey(c)); });
    return;
  }
  bits_.assign(static_cast<std::size_t>(dims_.prod()), 0);
  for (const auto& [l, h] : boxes)
    ForCells(l, h, [&](const Eigen::Vector3i& c) { bits_[At(c)] = 1; });
  for (int axis = 0; axis < 3; ++axis) {
    for (int step = 0; step < grow_; ++step) Dilate(axis);
  }
}

bool NearCells::Near(const Eigen::Vector3d& p) const { return Contains(CellOf(p, cell_)); }

std::vector<NearCells::Box> NearCells::Boxes(const io::TriangleMesh& mesh, Eigen::Vector3i* hi) {
  std::vector<Box> boxes(mesh.num_triangles());
  lo_ = Eigen::Vector3i::Constant(std::numeric_limits<int>::max());
  *hi = Eigen::Vector3i::Constant(std::numeric_limits<int>::min());
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
    boxes[t] = {CellOf(a.cwiseMin(b).cwiseMin(c), cell_), CellOf(a.cwiseMax(b).cwiseMax(c), cell_)};
    lo_ = lo_.cwiseMin(boxes[t].first);
    *hi = hi->cwiseMax(boxes[t].second);
  }
  return boxes;
}

bool NearCells::Contains(const Eigen::Vector3i& c) const {
  if (bits_.empty()) return set_.count(CellKey(c)) > 0;
  const Eigen::Vector3i i = c - lo_;
  if ((i.array() < 0).any() || (i.cast<std::int64_t>().array() >= dims_.array()).any())
    return false;
  return bits_[At(c)] != 0;
}

std::size_t NearCells::At(const Eigen::Vector3i& c) const {
  const Eigen::Matrix<std::int64_t, 3, 1> i = (c - lo_).cast<std::int64_t>();
  return static_cast<std::size_t>(i.x() + dims_.x() * (i.y() + dims_.y() * i.z()));
}

// Every cell also marked when a neighbour along `axis` is: each line of cells along the axis ORs
// in the lines before and after it (the box was grown by grow_, so nothing marked reaches its
// border).
void NearCells::Dilate(int axis) {
  const auto stride = static_cast<std::size_t>(axis == 0   ? 1
                                               : axis == 1 ? dims_.x()
                                                           : dims_.x() * dims_.y());
  const auto n = static_cast<std::size_t>(dims_[axis]);
  const std::size_t outer = bits_.size() / (stride * n);
  const std::vector<std::uint8_t> before = bits_;
  for (std::size_t o = 0; o < outer; ++o) {
    for (std::size_t a = 0; a < n; ++a) {
      const std::size_t line = (o * n + a) * stride;
      std::uint8_t* out = &bits_[line];
      if (a > 0) {
        const std::uint8_t* prev = &before[line - stride];
        for (std::size_t k = 0; k < stride; ++k) out[k] |= prev[k];
      }
      if (a + 1 < n) {
        const std::uint8_t* next = &before[line + stride];
        for (std::size_t k = 0; k < stride; ++k) out[k] |= next[k];
      }
    }
  }
}

}  // namespace occlude::app
