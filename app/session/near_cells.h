// Where a point may lie within a reach of a mesh: a conservative cull of points before an exact
// distance search (the report's vertex maps).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <unordered_set>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// The cells within `grow` cells (per axis) of a cell that the bounding box of one of the mesh's
/// triangles touches, with grow * cell >= reach: a point whose cell is not among them is farther
/// than `reach` from the mesh. Cells of half the reach grown by two, in a bitmap over the mesh's
/// box of cells (the boxes marked, then dilated one axis at a time): a thinner shell of
/// candidates than cells of the reach grown by one (on a-bite's jaws a third fewer of the points
/// searched to the whole reach in vain). When that bitmap would be huge (a stray vertex far away),
/// cells of the reach grown by one in a hash set. Depends on the mesh and the reach alone.
class NearCells {
 public:
  NearCells() = default;  ///< near nothing
  NearCells(const io::TriangleMesh& mesh, double reach_mm);

  /// False: p is farther than the reach from the mesh.
  bool Near(const Eigen::Vector3d& p) const;

  double reach_mm() const { return reach_mm_; }
  /// True when the cells are held in a hash set (the mesh's box of cells is too large a bitmap).
  bool hashed() const { return !set_.empty(); }

 private:
  using Box = std::pair<Eigen::Vector3i, Eigen::Vector3i>;
  /// Each triangle's box of cells (of cell_), and the box of them all (lo_, *hi).
  std::vector<Box> Boxes(const io::TriangleMesh& mesh, Eigen::Vector3i* hi);
  bool Contains(const Eigen::Vector3i& c) const;
  std::size_t At(const Eigen::Vector3i& c) const;
  void Dilate(int axis);

  double reach_mm_ = 0.0;
  double cell_ = 1.0;
  int grow_ = 1;
  Eigen::Vector3i lo_ = Eigen::Vector3i::Zero();
  Eigen::Matrix<std::int64_t, 3, 1> dims_ = Eigen::Matrix<std::int64_t, 3, 1>::Zero();
  std::vector<std::uint8_t> bits_;
  std::unordered_set<std::uint64_t> set_;
};

}  // namespace occlude::app
