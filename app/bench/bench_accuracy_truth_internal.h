// Ground truth of the speed-against-accuracy study (`occlude bench --accuracy`):
// the exact signed distance from a point to the lower jaw's triangles, and the
// fixed set of upper surface samples on which every method is scored.
//
// Exact signed distance (LowerDistance): the closest point over ALL lower
// triangles, found through a uniform grid (a dense array over the lower's
// bounds) of the triangles' bounding boxes, searched in growing shells of cells
// until no unvisited triangle can be closer,
// and signed by the angle-weighted pseudo-normal at that point
// (collision::PseudoNormals, the sign convention of the oracle, defined for open
// scans). It shares no search code with the oracle's distance field, so the
// oracle's exact level can be checked against it.
//
// Upper samples (UpperSamples): every upper triangle is split into k^2 congruent
// pieces, k = ceil(longest edge / spacing), and the pieces' centroids are its
// samples; each vertex is one more sample, owned by the first triangle that uses
// it. Deterministic (no seed); generated per triangle on demand, in the upper's
// own frame U. Sample ids run over all triangles (triangle t owns [begin(t), end(t))).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "occlude/collision/signed_distance.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::app {

/// Exact signed distance to one mesh (the lower jaw, frame L, mm). Not
/// thread-safe (the search keeps per-call marks); one instance per thread.
class LowerDistance {
 public:
  /// cell_mm: edge of the grid cells; 0 = the median longest triangle edge
  /// (clamped to [0.25, 5] mm), about the triangle size being best.
  explicit LowerDistance(std::shared_ptr<const io::TriangleMesh> lower_L, double cell_mm = 0.0);

  /// Exact signed distance from p_L (positive outside, the side the outward
  /// normals point to) when some triangle lies within max_mm of p_L; false
  /// (d untouched) when none does.
  bool Signed(const Eigen::Vector3d& p_L, double max_mm, double* d) const;

  /// Quick conservative filter: false only when no triangle's bounding box comes
  /// within max_mm of p_L (checked on a coarse occupancy grid).
  bool MayBeWithin(const Eigen::Vector3d& p_L, double max_mm) const;

  const io::TriangleMesh& mesh() const { return *mesh_; }

 private:
  using Cell = Eigen::Vector3i;
  /// A dense grid over the mesh's bounding box (cells outside it are empty).
  struct Grid {
    double size = 1.0;
    Eigen::Vector3i dims = Eigen::Vector3i::Ones();
    /// Linear index of cell c, or -1 outside the grid.
    long Index(const Cell& c) const {
      if ((c.array() < 0).any() || (c.array() >= dims.array()).any()) return -1;
      return c.x() + static_cast<long>(dims.x()) * (c.y() + static_cast<long>(dims.y()) * c.z());
    }
    std::size_t count() const {
      return static_cast<std::size_t>(dims.x()) * static_cast<std::size_t>(dims.y()) *
             static_cast<std::size_t>(dims.z());
    }
  };
  Cell CellOf(const Eigen::Vector3d& p, double size) const;
  Grid MakeGrid(double size) const;
  void Visit(const Cell& c, const Eigen::Vector3d& p, double* best2, std::uint32_t* best_t,
             Eigen::Vector3d* best_bary) const;

  std::shared_ptr<const io::TriangleMesh> mesh_;
  collision::PseudoNormals normals_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::AlignedBox3d bounds_;
  Grid fine_, coarse_;
  std::vector<std::uint32_t> cell_begin_;  // CSR over fine_ cells: size count() + 1
  std::vector<std::uint32_t> cell_triangles_;
  std::vector<std::uint8_t> coarse_occupied_;  // per coarse_ cell
  mutable std::vector<std::uint32_t> seen_;    // seen_[t] == epoch_: tested in this call
  mutable std::uint32_t epoch_ = 0;
};

/// The fixed upper sample set (see the file comment).
class UpperSamples {
 public:
  UpperSamples(std::shared_ptr<const io::TriangleMesh> upper_U, double spacing_mm);

  std::size_t num_triangles() const { return centre_U_.size(); }
  std::size_t size() const { return begin_.back(); }
  std::uint32_t begin(std::size_t t) const { return begin_[t]; }
  std::uint32_t end(std::size_t t) const { return begin_[t + 1]; }
  /// Samples of triangle t in id order (positions in U).
  void Generate(std::size_t t, std::vector<Eigen::Vector3d>* p_U) const;
  /// Triangle owning sample `id`.
  std::uint32_t TriangleOf(std::uint32_t id) const;
  /// Centroid of triangle t and the largest distance of its corners from it.
  const Eigen::Vector3d& centre_U(std::size_t t) const { return centre_U_[t]; }
  double radius(std::size_t t) const { return radius_[t]; }
  double spacing_mm() const { return spacing_; }
  const io::TriangleMesh& mesh() const { return *mesh_; }

 private:
  std::shared_ptr<const io::TriangleMesh> mesh_;
  double spacing_ = 0.05;
  std::vector<std::uint32_t> begin_;      // size triangles + 1
  std::vector<std::uint16_t> pieces_;     // k per triangle
  std::vector<std::uint8_t> owned_mask_;  // bit c: corner c is owned (a vertex sample)
  std::vector<Eigen::Vector3d> centre_U_;
  std::vector<double> radius_;
};

}  // namespace occlude::app
