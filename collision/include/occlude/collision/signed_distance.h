// Signed distance from a point to a triangle mesh: exact (closest triangle,
// signed by angle-weighted pseudo-normals, Baerentzen & Aanaes 2005) and as a
// narrow-band field of trilinear voxels around the surface.
//
// Frame and units: everything is in the mesh's frame F, in mm.
// Sign: distance > 0 outside (the side the outward face normals point to),
// < 0 inside. The sign comes from surface orientation only, never from an
// inside/outside test, so it is defined for open meshes (scans, gingiva) and
// for multi-shell meshes (one closed shell per tooth plus an open gingiva).
// Open borders: a point whose closest surface point lies on a boundary edge
// (an edge of one face only: the border of a scan) or on a vertex of one
// counts as outside, whatever the side: beyond the border of an open surface
// there is no inside (otherwise scan borders make phantom penetrations of
// millimetres, measured on the c3/c4 intraoral cases).
// Limitation: with several shells the sign is the one with respect to the
// nearest shell's surface; a point inside shell A but nearer to a face of an
// overlapping shell B that lies inside A gets B's sign (positive when outside B).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "occlude/collision/key_index_hash.h"
#include "occlude/collision/morton.h"
#include "occlude/collision/voxel_grid.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::collision {

/// Pseudo-normals of a mesh for signing distances (computed once, O(T log T)).
/// Face normal: unit (b - a) x (c - a) (zero for a degenerate face). Edge
/// pseudo-normal: sum of the face normals of the faces sharing the edge (one
/// face on a boundary edge of an open mesh; all of them on a non-manifold
/// edge). Vertex pseudo-normal: sum over incident faces of the face normal
/// times the face's angle at the vertex. Stored as floats (only directions
/// matter; the sign test has a wide margin except for p on the surface).
class PseudoNormals {
 public:
  PseudoNormals() = default;
  explicit PseudoNormals(const io::TriangleMesh& mesh);

  /// Pseudo-normal (not unit) at the closest point of triangle t given the
  /// barycentric weights of that point: the vertex one when two weights are
  /// ~0 (below kZeroWeight), the edge one when one weight is ~0, else the face
  /// normal.
  Eigen::Vector3d At(std::uint32_t t, const Eigen::Vector3d& barycentric) const;

  /// True when the closest point given by its barycentric weights lies on a
  /// boundary edge of the mesh or on a vertex of one (same weight rule as At).
  bool OnBoundary(std::uint32_t t, const Eigen::Vector3d& barycentric) const;
  /// Signed distance of p given its closest point on triangle t (barycentric
  /// weights): |p - closest| signed by the pseudo-normal; + on open borders.
  double Signed(std::uint32_t t, const Eigen::Vector3d& barycentric, const Eigen::Vector3d& p,
                const Eigen::Vector3d& closest, Eigen::Vector3d* unit_gradient) const;

  /// Unit face normal of t (zero when degenerate).
  Eigen::Vector3d Face(std::uint32_t t) const { return faces_[t].cast<double>(); }
  /// Pseudo-normal of edge k of t: the edge opposite corner k.
  Eigen::Vector3d Edge(std::uint32_t t, int k) const { return edges_[3 * t + k].cast<double>(); }
  /// Pseudo-normal of vertex v.
  Eigen::Vector3d Vertex(std::uint32_t v) const { return vertices_[v].cast<double>(); }

  std::size_t num_triangles() const { return faces_.size(); }
  std::size_t MemoryBytes() const;

  /// Barycentric weights below this count as zero (point on an edge/vertex).
  static constexpr double kZeroWeight = 1e-9;

 private:
  friend struct detail::OracleCodec;
  std::vector<Eigen::Vector3f> faces_;     ///< per triangle
  std::vector<Eigen::Vector3f> edges_;     ///< 3 per triangle (edge k opposite corner k)
  std::vector<Eigen::Vector3f> vertices_;  ///< per vertex
  std::vector<Eigen::Vector3i> corners_;   ///< vertex indices per triangle
  std::vector<bool> boundary_edge_;        ///< 3 per triangle, as edges_
  std::vector<bool> boundary_vertex_;      ///< per vertex: on a boundary edge
};

struct SignedDistanceSample {
  double distance = 0.0;                              ///< signed, mm
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();  ///< closest point on the mesh, F
  /// Unit gradient of the signed distance at the query point: (p - closest) /
  /// |p - closest| times the sign; the unit pseudo-normal when p is on the surface.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  std::uint32_t triangle = 0;  ///< the closest triangle
};

/// Signed distance from p_F to `mesh` by brute force over all triangles
/// (reference for tests; O(T)). False for an empty mesh.
bool SignedDistanceBruteForce(const io::TriangleMesh& mesh, const PseudoNormals& normals,
                              const Eigen::Vector3d& p_F, SignedDistanceSample* out);

struct NarrowBandOptions {
  /// Band = surface voxels dilated by this many voxels (cube neighbourhood,
  /// both sides of the surface); in [0, 16].
  int dilation_voxels = 2;
  /// Threads of the build (0 = every core); the field is the same for any count.
  int threads = 0;
  /// False: an exact-only field, without the band's corner values (their computation is most
  /// of a build). Exact and Sign answer as with them; Interpolate, CellValue and the band
  /// queries answer nothing (false, empty).
  bool corner_values = true;
};

namespace detail {

/// A sparse set of voxels stored as 4x4x4 bricks: brick key (voxel Morton key
/// >> 6) -> 64-bit occupancy mask (bit = voxel key & 63). After Finish(), the
/// bricks are sorted by key and Rank(key) is the voxel's index in the sorted
/// order of all voxel keys of the set.
class BrickSet {
 public:
  struct Brick {
    std::uint64_t key = 0;
    std::uint64_t mask = 0;
    std::uint32_t first = 0;  ///< rank of the brick's first voxel (after Finish)
  };
  /// Adds voxel `key` (Finish() needed before Rank/Find).
  void Add(std::uint64_t key);
  /// Grows the set by one voxel along `axis` (0..2) upward and/or downward.
  /// Coordinates must stay in [0, 2^21) (callers shift them).
  void Dilate(int axis, bool up, bool down);
  /// Sorts the bricks, computes ranks and the key index.
  void Finish();
  /// Index of brick `brick_key` in bricks() (after Finish), or KeyIndexHash::kNotFound.
  std::uint32_t BrickIndex(std::uint64_t brick_key) const { return index_.Find(brick_key); }
  /// The same for the brick at brick coordinates (x, y, z): one load from a
  /// dense index over the bricks' bounding box when Finish could afford one
  /// (4 bytes per box cell, at most 32 cells per brick), else the hash.
  /// Coordinates out of the box (or of the key range) find nothing.
  std::uint32_t BrickIndexAt(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    if (dense_.empty()) {
      constexpr std::uint32_t kLimit = 1u << 19;  // brick coordinates of 21-bit voxel keys
      if (x >= kLimit || y >= kLimit || z >= kLimit) return KeyIndexHash::kNotFound;
      return index_.Find(
          MortonEncode(static_cast<int>(x), static_cast<int>(y), static_cast<int>(z)));
    }
    const std::uint32_t* slot = DenseSlot(x, y, z);
    return slot == nullptr ? KeyIndexHash::kNotFound : *slot;
  }
  /// Asks the cache for what BrickIndexAt(x, y, z) will read (the dense index's
  /// entry; nothing when the hash serves), so that a later lookup does not wait.
  void PrefetchIndexAt(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    if (dense_.empty()) return;
    if (const std::uint32_t* slot = DenseSlot(x, y, z)) __builtin_prefetch(slot);
  }
  const Brick* FindAt(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    const std::uint32_t i = BrickIndexAt(x, y, z);
    return i == KeyIndexHash::kNotFound ? nullptr : &bricks_[i];
  }
  const Brick* Find(std::uint64_t brick_key) const {
    const std::uint32_t i = index_.Find(brick_key);
    return i == KeyIndexHash::kNotFound ? nullptr : &bricks_[i];
  }
  /// Index of voxel `key` in the sorted set, or KeyIndexHash::kNotFound.
  std::uint32_t Rank(std::uint64_t key) const {
    const Brick* b = Find(key >> 6);
    const int bit = static_cast<int>(key & 63);
    if (b == nullptr || ((b->mask >> bit) & 1) == 0) return KeyIndexHash::kNotFound;
    return b->first + PopCount(b->mask & ((std::uint64_t{1} << bit) - 1));
  }
  const std::vector<Brick>& bricks() const { return bricks_; }
  std::size_t num_voxels() const { return voxels_; }
  std::size_t MemoryBytes() const {
    return bricks_.capacity() * sizeof(Brick) + index_.MemoryBytes() +
           dense_.capacity() * sizeof(std::uint32_t);
  }
  static std::uint32_t PopCount(std::uint64_t x) {
    x -= (x >> 1) & 0x5555555555555555ULL;
    x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
    x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fULL;
    return static_cast<std::uint32_t>((x * 0x0101010101010101ULL) >> 56);
  }

 private:
  friend struct OracleCodec;
  Brick& At(std::uint64_t brick_key);
  void BuildDense();
  /// The dense index's entry for brick (x, y, z), or null outside its box (dense_ built).
  const std::uint32_t* DenseSlot(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    x -= dense_lo_[0];
    y -= dense_lo_[1];
    z -= dense_lo_[2];
    if (x >= dense_dims_[0] || y >= dense_dims_[1] || z >= dense_dims_[2]) return nullptr;
    return &dense_[x + dense_dims_[0] * (static_cast<std::size_t>(y) +
                                         dense_dims_[1] * static_cast<std::size_t>(z))];
  }
  std::vector<Brick> bricks_;
  KeyIndexHash index_;
  std::size_t voxels_ = 0;
  std::vector<std::uint32_t> dense_;  ///< brick index per box cell (x fastest), or kNotFound
  std::uint32_t dense_lo_[3] = {0, 0, 0};
  std::uint32_t dense_dims_[3] = {0, 0, 0};
};

}  // namespace detail

/// Narrow-band signed distance field of one mesh over its sparse voxel grid.
/// Immutable after Build; const queries are thread-safe. Deterministic.
class NarrowBandSdf {
 public:
  NarrowBandSdf() = default;

  /// Builds from the mesh and its voxel grid (Voxelize of this mesh at some
  /// voxel size s; only the surface voxels are used). Stores, for every voxel
  /// of the band, the 8 corner signed distances as floats: exact (closest
  /// triangle over the whole mesh, found through the surface voxels, signed by
  /// pseudo-normals), grouped by 4x4x4 bricks of voxels (5x5x5 corners each)
  /// found through a hash of brick keys.
  /// Throws std::invalid_argument for a null mesh, a grid that does not match
  /// the mesh (triangle index out of range, s <= 0) or a bad option.
  static NarrowBandSdf Build(std::shared_ptr<const io::TriangleMesh> mesh, const VoxelGrid& grid,
                             const NarrowBandOptions& options = {});

  /// Trilinear signed distance (mm) at p_F with its gradient in F (the analytic
  /// derivative of the trilinear interpolant, ~unit). False when p_F's voxel
  /// is not in the band (outputs untouched).
  bool Interpolate(const Eigen::Vector3d& p_F, double* distance,
                   Eigen::Vector3d* gradient = nullptr) const;

  /// Voxel-level answer: the value at the centre of the voxel containing p_F
  /// (mean of its 8 corners), mm; false outside the band.
  bool CellValue(const Eigen::Vector3d& p_F, double* distance) const;

  /// Exact signed distance using the triangles of the surface voxels that can
  /// hold a point within max_distance of p_F (a subset of those within
  /// ceil(max_distance / s) + 1 voxels), so it is exact whenever |true
  /// distance| <= max_distance; false if no triangle is within max_distance.
  bool Exact(const Eigen::Vector3d& p_F, double max_distance, SignedDistanceSample* out) const;

  /// Guarantee: every point within band_mm() = dilation_voxels * s of the
  /// surface lies in a band voxel (its closest point lies in a surface voxel,
  /// and a displacement of at most d * s moves the voxel index by at most d
  /// per axis).
  double band_mm() const { return band_mm_; }
  double voxel_size_mm() const { return s_; }
  /// The band voxels where the field takes values in [-depth, value] (their
  /// corners' range meets it: a trilinear value lies between its voxel's
  /// smallest and largest corner) together with the surface voxels, as a grid
  /// of their own: voxel (i, j, k) of this field is voxel (i, j, k) +
  /// band_key_shift() of the result (band voxels reach below index 0), same
  /// voxel size, origin shifted to match; only voxel_size_mm, origin_F, dims
  /// and surface_keys are set (enough for DistanceBound::Build).
  VoxelGrid BandVoxelsWithin(float depth, float value, int threads = 1) const;
  /// The same at a finer grain: each band voxel split into split^3 cells (voxel
  /// size / split), keeping the cells where the trilinear field takes values in
  /// [-depth, value] (a trilinear function's extremes over a cell lie at its
  /// corners, whose values are interpolated from the voxel's) and every cell
  /// of the surface voxels. Cell (a, b, c) of voxel (i, j, k) is cell
  /// split * ((i, j, k) + band_key_shift()) + (a, b, c) of the result; the keys
  /// are sorted. split = 1 gives BandVoxelsWithin's set. `threads` workers (0 =
  /// every core; the same set for any count). Throws std::invalid_argument
  /// unless 1 <= split <= 8 and threads >= 0.
  VoxelGrid BandCellsWithin(float depth, float value, int split, int threads = 1) const;
  int band_key_shift() const { return shift_; }
  std::size_t num_band_voxels() const { return band_.num_voxels(); }
  /// Bytes held by this object (the shared mesh is not counted).
  std::size_t MemoryBytes() const;
  double build_seconds() const { return build_seconds_; }
  const PseudoNormals& pseudo_normals() const { return normals_; }

 private:
  friend class SdfSampler;  // fast repeated lookups (sdf_sampler.h)
  friend struct detail::OracleCodec;

  /// A triangle's corners and bounding sphere, stored in spatial (Morton) order
  /// so that the triangles of neighbouring voxels are close in memory.
  struct PackedTriangle {
    Eigen::Vector3d a, b, c;
    Eigen::Vector3d center;
    double radius = 0.0;
  };
  struct Nearest {
    std::uint32_t triangle = 0;  ///< internal index (see original_)
    double squared_distance = 0.0;
    double distance = 0.0;  ///< sqrt(squared_distance), for culling
    Eigen::Vector3d closest = Eigen::Vector3d::Zero();
    Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
    /// Optional per-search marks (build only): triangle t was tested when seen[t] == epoch.
    std::vector<std::uint32_t>* seen = nullptr;
    std::uint32_t epoch = 0;
  };

  void CopyGrid(const VoxelGrid& grid);
  /// Packs the triangles in spatial order and renumbers the grid's lists.
  void PackTriangles();
  detail::BrickSet BandVoxels(const VoxelGrid& grid, int dilation) const;
  /// BandCellsWithin's cells of voxel `bit` of band brick `brick`, appended to keys.
  void BandVoxelCells(std::size_t brick, int bit, float depth, float value, int split,
                      std::vector<std::uint64_t>* keys) const;
  std::vector<float> CornerValues(const detail::BrickSet& corners, int threads) const;
  struct CornerScratch;  ///< per-thread buffers of CornerValues (signed_distance_corners.cpp)
  /// The exact signed distances at the corners of brick `bi` of `corners`
  /// (into value[rank]), from one candidate list of triangles for the brick.
  void BrickCornerValues(const detail::BrickSet& corners, std::size_t bi, CornerScratch* scratch,
                         std::vector<float>* value) const;
  void ScanCandidates(const CornerScratch& scratch, const Eigen::Vector3d& p, Nearest* best,
                      bool* found) const;
  /// Appends the triangles of the surface voxels whose cubes lie within R (mm) of the box
  /// [box_lo, box_hi] (voxel coordinates), each once, to the scratch's candidates (in voxel
  /// order).
  void GatherCandidates(const Eigen::Vector3d& box_lo, const Eigen::Vector3d& box_hi, double R,
                        CornerScratch* scratch) const;
  void AddVoxelCandidates(std::size_t voxel, CornerScratch* scratch) const;
  void FillBlocks(const detail::BrickSet& band, int threads);
  /// Closest triangle to p among those within sqrt(bound2); `hint` (a triangle
  /// index or kNoHint) seeds the search. False when none is within.
  bool FindNearest(const Eigen::Vector3d& p, double bound2, std::uint32_t hint,
                   Nearest* best) const;
  void ScanBrick(const Eigen::Vector3d& q, const Eigen::Vector3i& brick,
                 const detail::BrickSet::Brick& b, const Eigen::Vector3d& p, Nearest* best,
                 bool* found) const;
  void TestTriangle(std::uint32_t t, const Eigen::Vector3d& p, Nearest* best, bool* found) const;
  SignedDistanceSample Sign(const Eigen::Vector3d& p, const Nearest& n) const;
  /// Corner values of the band voxel holding p (its corner (0,0,0) within its
  /// brick; corner o at + kCornerStep[o]) and p's local coordinates in the
  /// voxel; null outside the band.
  const float* Locate(const Eigen::Vector3d& p, Eigen::Vector3f* local) const;

  static constexpr std::uint32_t kNoHint = 0xffffffffu;

  std::shared_ptr<const io::TriangleMesh> mesh_;
  PseudoNormals normals_;
  std::vector<PackedTriangle> packed_;   ///< internal (spatial) triangle order
  std::vector<std::uint32_t> original_;  ///< internal index -> mesh triangle index
  double s_ = 0.0;
  double inv_s_ = 0.0;
  double band_mm_ = 0.0;
  double build_seconds_ = 0.0;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  int shift_ = 0;  ///< band voxel (i,j,k) is keyed by Morton(i+shift, j+shift, k+shift)
  std::vector<std::uint32_t> tri_offsets_;  ///< CSR, as in VoxelGrid
  std::vector<std::uint32_t> tri_indices_;
  detail::BrickSet surface_;  ///< grid keys; rank = index into the CSR
  /// The corner values of one 4x4x4 brick of band voxels: its 5x5x5 corners
  /// (x + 5 y + 25 z), mm, stored together so that one hash probe and one or
  /// two cache lines serve a query (a block per voxel measured 150-290 ns per
  /// call on a whole jaw, mostly cache misses). Corners that no band voxel of
  /// the brick uses are 0 and never read.
  struct alignas(64) CornerBrick {
    std::uint64_t mask = 0;  ///< band voxels of the brick (BrickSet mask)
    float value[125] = {};
  };
  /// One corner brick of `brick` (a band brick) from the corner values (value[rank in corners]).
  static void FillCornerBrick(const detail::BrickSet::Brick& brick, const detail::BrickSet& corners,
                              const std::vector<float>& value, CornerBrick* out);
  detail::BrickSet band_;  ///< shifted keys; brick i <-> corner_bricks_[i]
  std::vector<CornerBrick> corner_bricks_;
  /// The corner brick at brick coordinates (bx, by, bz) (of shifted voxel
  /// coordinates >> 2, each < 2^19), or null.
  const CornerBrick* BrickAt(std::uint32_t bx, std::uint32_t by, std::uint32_t bz) const {
    const std::uint32_t i = band_.BrickIndexAt(bx, by, bz);
    return i == detail::KeyIndexHash::kNotFound ? nullptr : &corner_bricks_[i];
  }
};

}  // namespace occlude::collision
