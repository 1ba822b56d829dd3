// Scoring of `occlude bench --accuracy`: what a method answered at one pose,
// turned into claims about the upper surface, and each claim checked against
// the ground truth (bench_accuracy_truth_internal.h). The definitions here are the ones
// the accuracy CSV's header and the README state:
//
// Truth at a pose X_LU: d*(s), the exact signed distance of each fixed upper
// sample s (placed by X_LU) to the lower triangles. A truth contact is a
// sample with d*(s) <= delta (touching or interpenetrating); the true depth is
// max(0, -min d*) over the samples (depths are measured to kDepthLimitMm).
//
// A method's answer is a list of claims, each "within the band":
//  - point claim (p, d): the upper surface point p lies at signed distance d
//    (oracle contacts and penetrations, the closest point of each upper triangle
//    of the exact pair query, FCL's nearest point). Error |d - d*(p)|; false
//    when d*(p) > delta.
//  - region claim (element, b): some point of an upper element (a voxel of the
//    method's grid, or a triangle) lies within b of the lower surface (IST voxel
//    pairs: b = delta; FCL intersecting triangles: b = 0). With D = the smallest
//    d* over the element's truth samples and h the truth spacing (every point of
//    the element is within h of a sample and d* is 1-Lipschitz, so the element
//    comes no closer than D - h): error max(0, D - h - b); false when D - h >
//    delta; unscored when the element holds no truth sample.
// A truth contact s is covered when a claim speaks for it: a point claim within
// the method's sample spacing of s (oracle sub-voxel/exact), a claim in the
// upper voxel holding s (oracle voxel level, IST voxel pairs), or a claim on the
// triangle holding s (exact pairs, FCL). Missed = truth contacts not covered.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "bench/bench_accuracy_truth_internal.h"
#include "occlude/collision/voxel_grid.h"

namespace occlude::app {

/// Samples deeper than this inside the lower jaw, and claims farther than
/// kClaimSearchMm from it, are beyond the truth's search (see the file comment).
inline constexpr double kDepthLimitMm = 1.0;
inline constexpr double kClaimSearchMm = 3.0;

struct Claim {
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();  ///< point claims: the point, in L
  double d_mm = 0.0;          ///< point: the claimed signed distance; region: the band b
  std::int64_t element = -1;  ///< upper voxel index (into grid) or upper triangle; -1 = none
};

enum class Cover {
  kRadius,    ///< a point claim within radius_mm of the sample
  kVoxel,     ///< a claim in the sample's voxel of `grid` (frame U)
  kTriangle,  ///< a claim on the sample's triangle
  kNone,      ///< the query lists no contacts (distance queries): missed/false not defined
};

struct Answer {
  bool region = false;  ///< claims are region claims (else point claims)
  Cover cover = Cover::kRadius;
  double radius_mm = 0.0;
  const collision::VoxelGrid* grid =
      nullptr;  ///< kVoxel and voxel regions: the method's upper grid
  std::vector<Claim> claims;
  bool has_depth = false;  ///< the method states a penetration depth
  double max_penetration_mm = 0.0;
};

/// Truth at one pose: the truth contacts, the true depth, and a cache of d*
/// for every sample evaluated so far (shared by all answers scored at the pose).
class PoseTruth {
 public:
  PoseTruth(const LowerDistance& lower, const UpperSamples& samples, const Eigen::Isometry3d& X_LU,
            double delta_mm);

  const Eigen::Isometry3d& X_LU() const { return X_LU_; }
  double delta_mm() const { return delta_; }
  /// Truth contacts: sample ids, positions in U and d*.
  const std::vector<std::uint32_t>& contact_ids() const { return contact_ids_; }
  const std::vector<Eigen::Vector3d>& contact_p_U() const { return contact_p_U_; }
  const std::vector<float>& contact_d() const { return contact_d_; }
  double max_penetration_mm() const { return max_penetration_; }
  /// d* of a point given in L (+kClaimSearchMm when beyond the search).
  double DistanceAt(const Eigen::Vector3d& p_L) const;
  /// Smallest d* over the truth samples of an upper triangle, or (VoxelMins) of
  /// the samples of a voxel's triangles that lie in the voxel grown by the
  /// truth spacing h (so every surface point of the voxel has one within h);
  /// +inf when it has no sample. Stops early with some value <= stop_mm once
  /// one is found (the caller only needs to know that the minimum is at most
  /// stop_mm).
  double TriangleMin(std::uint32_t t, double stop_mm);
  /// The voxel minimum for each of `voxels` (indices into grid_U.surface_keys),
  /// with each triangle's samples generated once.
  std::vector<double> VoxelMins(const collision::VoxelGrid& grid_U,
                                const std::vector<std::uint32_t>& voxels, double stop_mm);
  const UpperSamples& samples() const { return samples_; }
  /// Forgets the cached d* (the truth contacts are kept).
  void ClearCache() { std::unordered_map<std::uint32_t, float>().swap(cache_); }

 private:
  /// d* of sample `id` at p_U when |d*| <= bound (cached); +inf otherwise.
  double SampleDistance(std::uint32_t id, const Eigen::Vector3d& p_U, double bound);
  /// Minimum over the listed samples (ids and positions), stopping at stop_mm.
  double MinOver(const std::vector<std::uint32_t>& ids, const std::vector<Eigen::Vector3d>& p_U,
                 double stop_mm);

  const LowerDistance& lower_;
  const UpperSamples& samples_;
  Eigen::Isometry3d X_LU_;
  double delta_;
  std::vector<std::uint32_t> contact_ids_;
  std::vector<Eigen::Vector3d> contact_p_U_;
  std::vector<float> contact_d_;
  double max_penetration_ = 0.0;
  std::unordered_map<std::uint32_t, float> cache_;  // id -> d* (exact below kClaimSearchMm)
  std::vector<Eigen::Vector3d> scratch_;
};

/// Totals of one method over all poses.
struct Score {
  std::vector<double> errors;      ///< one per scored claim, mm
  std::vector<double> pen_errors;  ///< one per pose (methods stating a depth), mm
  std::size_t claims = 0, unscored = 0;
  std::size_t truth_contacts = 0, truth_half = 0;  ///< d* <= delta; |d*| <= delta / 2
  std::size_t missed = 0, missed_half = 0;
  std::size_t false_contacts = 0, false_double = 0;  ///< truth > delta, truth > 2 delta
  bool contacts_defined = true;                      ///< false for Cover::kNone
};

/// Index of the surface voxel of grid_U holding p_U (frame U), or -1.
std::int64_t SurfaceVoxelOf(const collision::VoxelGrid& grid_U, const Eigen::Vector3d& p_U);

/// Adds `from` to `to` (the same answer scored once for several methods).
void MergeScore(const Score& from, Score* to);

/// Scores `answer` at the pose and adds it to `score`.
void ScoreAnswer(const Answer& answer, PoseTruth* truth, Score* score);

}  // namespace occlude::app
