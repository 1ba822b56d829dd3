// Spike patches: scanner artefacts among the penetrating samples. Penetrating
// samples within a link distance of each other form a patch; a patch deeper
// than the radius of a disc of its area is steeper than a hemisphere pressed
// into a plane (depth h over a cap of area 2 pi R h, i.e. h > R: a crown pushed
// deeper than its own radius of curvature), which smooth enamel does not do
// and scan spikes, folds and flaps do. Such patches up to a size cap are
// outliers of the penetration measure (still reported).
#include <algorithm>
#include <cmath>
#include <numeric>

#include "occlude/angles.h"
#include "occlude/planner/evaluation.h"

namespace occlude::planner {
namespace {

std::uint64_t CellKey(const Eigen::Vector3i& c) {
  auto u = [](int v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff; };
  return (u(c.x()) << 42) | (u(c.y()) << 21) | u(c.z());
}

int Find(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

}  // namespace

std::vector<PenetrationPatch> PenetrationPatches(const std::vector<PenetratingSample>& samples,
                                                 double link_mm, double max_spike_area_mm2) {
  const int n = static_cast<int>(samples.size());
  std::vector<int> parent(samples.size());
  std::iota(parent.begin(), parent.end(), 0);
  // Cells of size link_mm as a sorted (key, sample) list: no allocation per cell.
  auto cell_of = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / link_mm)),
                           static_cast<int>(std::floor(p.y() / link_mm)),
                           static_cast<int>(std::floor(p.z() / link_mm)));
  };
  std::vector<std::pair<std::uint64_t, int>> keyed(samples.size());
  for (int i = 0; i < n; ++i) {
    keyed[static_cast<std::size_t>(i)] = {
        CellKey(cell_of(samples[static_cast<std::size_t>(i)].p_L)), i};
  }
  std::sort(keyed.begin(), keyed.end());
  const double link2 = link_mm * link_mm;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d& p = samples[static_cast<std::size_t>(i)].p_L;
    const Eigen::Vector3i c = cell_of(p);
    for (int d = 0; d < 27; ++d) {
      const std::uint64_t key = CellKey(c + Eigen::Vector3i(d % 3 - 1, (d / 3) % 3 - 1, d / 9 - 1));
      auto it = std::lower_bound(keyed.begin(), keyed.end(), std::make_pair(key, 0));
      for (; it != keyed.end() && it->first == key; ++it) {
        const int j = it->second;
        if (j <= i || (samples[static_cast<std::size_t>(j)].p_L - p).squaredNorm() > link2)
          continue;
        const int a = Find(parent, i), b = Find(parent, j);
        if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
      }
    }
  }
  // Patches in order of their smallest member (deterministic).
  std::vector<PenetrationPatch> patches;
  std::vector<int> patch_of(samples.size(), -1);
  for (int i = 0; i < n; ++i) {
    const int root = Find(parent, i);
    int& k = patch_of[static_cast<std::size_t>(root)];
    if (k < 0) {
      k = static_cast<int>(patches.size());
      patches.emplace_back();
    }
    PenetrationPatch& patch = patches[static_cast<std::size_t>(k)];
    const PenetratingSample& s = samples[static_cast<std::size_t>(i)];
    patch.members.push_back(static_cast<std::size_t>(i));
    patch.area_mm2 += s.area_mm2;
    patch.centre_L += s.area_mm2 * s.p_L;
    if (s.depth_mm > patch.depth_mm) {
      patch.depth_mm = s.depth_mm;
      patch.deepest_L = s.p_L;
    }
  }
  for (PenetrationPatch& patch : patches) {
    if (patch.area_mm2 > 0.0) patch.centre_L /= patch.area_mm2;
    const double disc_radius = std::sqrt(patch.area_mm2 / kPi);
    patch.spike = patch.area_mm2 <= max_spike_area_mm2 && patch.depth_mm > disc_radius;
  }
  return patches;
}

std::vector<bool> SpikeMembers(const std::vector<PenetratingSample>& samples, double link_mm,
                               double max_spike_area_mm2) {
  std::vector<bool> spike(samples.size(), false);
  if (max_spike_area_mm2 <= 0.0) return spike;
  for (const PenetrationPatch& p : PenetrationPatches(samples, link_mm, max_spike_area_mm2)) {
    if (!p.spike) continue;
    for (const std::size_t i : p.members) spike[i] = true;
  }
  return spike;
}

std::vector<bool> SpikeMembersForMeasure(const std::vector<PenetratingSample>& samples,
                                         double link_mm, double max_spike_area_mm2, double limit_mm,
                                         double shallow_mm) {
  std::vector<bool> spike(samples.size(), false);
  if (max_spike_area_mm2 <= 0.0) return spike;
  double over_limit = 0.0;
  std::vector<PenetratingSample> deep;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples[i].depth_mm > limit_mm) over_limit += samples[i].area_mm2;
    if (samples[i].depth_mm <= shallow_mm) continue;
    deep.push_back(samples[i]);
    index.push_back(i);
  }
  if (over_limit > kNestedCaps * max_spike_area_mm2) return spike;
  const std::vector<bool> member = SpikeMembers(deep, link_mm, max_spike_area_mm2);
  for (std::size_t k = 0; k < deep.size(); ++k) spike[index[k]] = member[k];
  return spike;
}

}  // namespace occlude::planner
