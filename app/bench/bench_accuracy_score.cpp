// Scoring of the accuracy study (see bench_accuracy_score_internal.h).
#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "bench/bench_accuracy_score_internal.h"
#include "occlude/collision/morton.h"

namespace occlude::app {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Point claims hashed by cells of edge `radius` (frame U), for the coverage test.
class PointHash {
 public:
  PointHash(const std::vector<Eigen::Vector3d>& p_U, double radius) : points_(p_U), r_(radius) {
    for (std::size_t i = 0; i < points_.size(); ++i) cells_[Key(Cell(points_[i]))].push_back(i);
  }
  bool AnyWithin(const Eigen::Vector3d& p) const {
    const Eigen::Vector3i c = Cell(p);
    for (int z = -1; z <= 1; ++z)
      for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
          const auto it = cells_.find(Key(c + Eigen::Vector3i(x, y, z)));
          if (it == cells_.end()) continue;
          for (const std::size_t i : it->second)
            if ((points_[i] - p).squaredNorm() <= r_ * r_) return true;
        }
    return false;
  }

 private:
  Eigen::Vector3i Cell(const Eigen::Vector3d& p) const {
    return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / r_)),
                           static_cast<int>(std::floor(p.y() / r_)),
                           static_cast<int>(std::floor(p.z() / r_)));
  }
  static std::uint64_t Key(const Eigen::Vector3i& c) {
    auto u = [](int v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffffULL; };
    return u(c.x()) | (u(c.y()) << 21) | (u(c.z()) << 42);
  }
  const std::vector<Eigen::Vector3d>& points_;
  double r_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

}  // namespace

std::int64_t SurfaceVoxelOf(const collision::VoxelGrid& grid_U, const Eigen::Vector3d& p_U) {
  const Eigen::Vector3i v = grid_U.VoxelOf(p_U);
  if ((v.array() < 0).any() || (v.array() >= grid_U.dims.array()).any()) return -1;
  const std::uint64_t key = collision::MortonEncode(v);
  const auto it = std::lower_bound(grid_U.surface_keys.begin(), grid_U.surface_keys.end(), key);
  if (it == grid_U.surface_keys.end() || *it != key) return -1;
  return it - grid_U.surface_keys.begin();
}

PoseTruth::PoseTruth(const LowerDistance& lower, const UpperSamples& samples,
                     const Eigen::Isometry3d& X_LU, double delta_mm)
    : lower_(lower), samples_(samples), X_LU_(X_LU), delta_(delta_mm) {
  std::vector<Eigen::Vector3d> p_U;
  double min_d = kInf;
  for (std::size_t t = 0; t < samples_.num_triangles(); ++t) {
    const Eigen::Vector3d c_L = X_LU_ * samples_.centre_U(t);
    const double r = samples_.radius(t);
    if (!lower_.MayBeWithin(c_L, r + kDepthLimitMm)) continue;
    // d* is 1-Lipschitz: no sample of t is within delta when the centre is
    // farther than r + delta outside; a centre not found within r + the depth
    // limit is either that far outside or deeper than the limit.
    double d_c = 0.0;
    if (!lower_.Signed(c_L, r + kDepthLimitMm, &d_c) || d_c > r + delta_) continue;
    samples_.Generate(t, &p_U);
    for (std::size_t i = 0; i < p_U.size(); ++i) {
      const auto id = static_cast<std::uint32_t>(samples_.begin(t) + i);
      // Farther than the depth limit cannot be a contact or a measured depth.
      const double d = SampleDistance(id, p_U[i], std::max(delta_, kDepthLimitMm));
      min_d = std::min(min_d, d);
      if (d <= delta_) {
        contact_ids_.push_back(id);
        contact_p_U_.push_back(p_U[i]);
        contact_d_.push_back(static_cast<float>(d));
      }
    }
  }
  max_penetration_ = std::isfinite(min_d) ? std::max(0.0, -min_d) : 0.0;
  ClearCache();  // the contacts are kept; the other candidates' values are cheap to redo
}

double PoseTruth::SampleDistance(std::uint32_t id, const Eigen::Vector3d& p_U, double bound) {
  const auto it = cache_.find(id);
  if (it != cache_.end()) return it->second;
  double d = 0.0;
  if (lower_.Signed(X_LU_ * p_U, bound, &d)) {
    cache_.emplace(id, static_cast<float>(d));
    return d;
  }
  if (bound >= kClaimSearchMm) cache_.emplace(id, static_cast<float>(kInf));
  return kInf;
}

double PoseTruth::DistanceAt(const Eigen::Vector3d& p_L) const {
  double d = 0.0;
  return lower_.Signed(p_L, kClaimSearchMm, &d) ? d : kClaimSearchMm;
}

double PoseTruth::MinOver(const std::vector<std::uint32_t>& ids,
                          const std::vector<Eigen::Vector3d>& p_U, double stop_mm) {
  // d* is 1-Lipschitz: a sample within r of a known sample c has d* >= d*(c) - r,
  // so it cannot lower the minimum when d*(c) - r >= best. Known samples (exact
  // values, kept for the last kKnown evaluated) prune most of a far element.
  constexpr std::size_t kKnown = 64;
  std::vector<std::pair<Eigen::Vector3d, double>> known;
  std::size_t next = 0;
  double best = kInf;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    bool pruned = false;
    for (const auto& [c, d_c] : known) {
      if (d_c - (p_U[i] - c).norm() >= best) {
        pruned = true;
        break;
      }
    }
    if (pruned) continue;
    const double d = SampleDistance(ids[i], p_U[i], kClaimSearchMm);
    if (!std::isfinite(d)) continue;
    if (known.size() < kKnown) {
      known.emplace_back(p_U[i], d);
    } else {
      known[next] = {p_U[i], d};
      next = (next + 1) % kKnown;
    }
    best = std::min(best, d);
    if (best <= stop_mm) break;
  }
  return best;
}

double PoseTruth::TriangleMin(std::uint32_t t, double stop_mm) {
  samples_.Generate(t, &scratch_);
  std::vector<std::uint32_t> ids(scratch_.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
    ids[i] = static_cast<std::uint32_t>(samples_.begin(t) + i);
  return MinOver(ids, scratch_, stop_mm);
}

std::vector<double> PoseTruth::VoxelMins(const collision::VoxelGrid& grid_U,
                                         const std::vector<std::uint32_t>& voxels, double stop_mm) {
  // Samples of the voxels' triangles, bucketed by the claimed voxel they lie in.
  std::unordered_map<std::uint64_t, std::size_t> slot;  // Morton key -> index into voxels
  std::vector<std::uint32_t> triangles;
  for (std::size_t i = 0; i < voxels.size(); ++i) {
    slot.emplace(grid_U.surface_keys[voxels[i]], i);
    for (auto k = grid_U.triangles_begin(voxels[i]); k < grid_U.triangles_end(voxels[i]); ++k)
      triangles.push_back(grid_U.triangle_indices[k]);
  }
  std::sort(triangles.begin(), triangles.end());
  triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
  std::vector<std::vector<std::uint32_t>> ids(voxels.size());
  std::vector<std::vector<Eigen::Vector3d>> points(voxels.size());
  // A sample joins every claimed voxel within h of it (Chebyshev): then each
  // point of the surface in a voxel has a sample of that voxel within h.
  const double h = samples_.spacing_mm();
  for (const std::uint32_t t : triangles) {
    samples_.Generate(t, &scratch_);
    for (std::size_t k = 0; k < scratch_.size(); ++k) {
      const Eigen::Vector3i lo = grid_U.VoxelOf(scratch_[k] - Eigen::Vector3d::Constant(h));
      const Eigen::Vector3i hi = grid_U.VoxelOf(scratch_[k] + Eigen::Vector3d::Constant(h));
      for (int z = lo.z(); z <= hi.z(); ++z)
        for (int y = lo.y(); y <= hi.y(); ++y)
          for (int x = lo.x(); x <= hi.x(); ++x) {
            if (x < 0 || y < 0 || z < 0) continue;
            const auto it = slot.find(collision::MortonEncode(x, y, z));
            if (it == slot.end()) continue;
            ids[it->second].push_back(static_cast<std::uint32_t>(samples_.begin(t) + k));
            points[it->second].push_back(scratch_[k]);
          }
    }
  }
  std::vector<double> mins(voxels.size());
  for (std::size_t i = 0; i < voxels.size(); ++i) mins[i] = MinOver(ids[i], points[i], stop_mm);
  return mins;
}

void MergeScore(const Score& from, Score* to) {
  to->errors.insert(to->errors.end(), from.errors.begin(), from.errors.end());
  to->pen_errors.insert(to->pen_errors.end(), from.pen_errors.begin(), from.pen_errors.end());
  to->claims += from.claims;
  to->unscored += from.unscored;
  to->truth_contacts += from.truth_contacts;
  to->truth_half += from.truth_half;
  to->missed += from.missed;
  to->missed_half += from.missed_half;
  to->false_contacts += from.false_contacts;
  to->false_double += from.false_double;
  to->contacts_defined = to->contacts_defined && from.contacts_defined;
}

namespace {

// Each claim's error against the truth (and whether it is a false contact).
void ScoreClaims(const Answer& answer, PoseTruth* truth, Score* score) {
  const double delta = truth->delta_mm();
  auto judge = [&](double error, double truth_d) {
    score->errors.push_back(error);
    if (answer.cover == Cover::kNone) return;
    if (truth_d > delta) ++score->false_contacts;
    if (truth_d > 2.0 * delta) ++score->false_double;
  };
  // Region claims: the element's smallest d*, found exactly down to the
  // claimed band (below it the claim holds, so any value there will do).
  std::vector<double> region_min;
  if (answer.region && answer.grid != nullptr) {
    std::vector<std::uint32_t> voxels;
    double band = 0.0;
    for (const Claim& c : answer.claims) {
      voxels.push_back(static_cast<std::uint32_t>(c.element));
      band = std::max(band, c.d_mm);
    }
    region_min = truth->VoxelMins(*answer.grid, voxels, band);
  }
  for (std::size_t i = 0; i < answer.claims.size(); ++i) {
    const Claim& c = answer.claims[i];
    if (!answer.region) {
      const double d_true = truth->DistanceAt(c.p_L);
      judge(std::abs(c.d_mm - d_true), d_true);
      continue;
    }
    const double D = answer.grid != nullptr
                         ? region_min[i]
                         : truth->TriangleMin(static_cast<std::uint32_t>(c.element), c.d_mm);
    if (!std::isfinite(D)) {
      ++score->unscored;
      continue;
    }
    // Every point of the element is within the truth spacing h of a sample,
    // so its true minimum is at least D - h: judged by that lower bound.
    const double lower_bound = D - truth->samples().spacing_mm();
    judge(std::max(0.0, lower_bound - c.d_mm), lower_bound);
  }
}

// Which truth contacts a claim covers, by the answer's kind of cover.
void ScoreCoverage(const Answer& answer, PoseTruth* truth, Score* score) {
  const double delta = truth->delta_mm();
  const Eigen::Isometry3d X_UL = truth->X_LU().inverse();
  std::unordered_set<std::int64_t> elements;
  std::vector<Eigen::Vector3d> points_U;
  for (const Claim& c : answer.claims) {
    if (answer.cover == Cover::kRadius) {
      points_U.push_back(X_UL * c.p_L);
    } else {
      elements.insert(c.element);
    }
  }
  const PointHash hash(points_U, std::max(answer.radius_mm, 1e-6));
  const auto& ids = truth->contact_ids();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const Eigen::Vector3d& p_U = truth->contact_p_U()[i];
    bool covered = false;
    switch (answer.cover) {
      case Cover::kRadius:
        covered = hash.AnyWithin(p_U);
        break;
      case Cover::kVoxel:
        covered = elements.count(SurfaceVoxelOf(*answer.grid, p_U)) > 0;
        break;
      case Cover::kTriangle:
        covered = elements.count(truth->samples().TriangleOf(ids[i])) > 0;
        break;
      case Cover::kNone:
        break;
    }
    const bool half = std::abs(static_cast<double>(truth->contact_d()[i])) <= 0.5 * delta;
    ++score->truth_contacts;
    if (half) ++score->truth_half;
    if (!covered) {
      ++score->missed;
      if (half) ++score->missed_half;
    }
  }
}

}  // namespace

void ScoreAnswer(const Answer& answer, PoseTruth* truth, Score* score) {
  score->claims += answer.claims.size();
  ScoreClaims(answer, truth, score);
  if (answer.has_depth) {
    score->pen_errors.push_back(std::abs(answer.max_penetration_mm - truth->max_penetration_mm()));
  }
  if (answer.cover == Cover::kNone) {
    score->contacts_defined = false;
    return;
  }
  ScoreCoverage(answer, truth, score);
}

}  // namespace occlude::app
