// The intercuspation basins of the synthetic jaw pair along the arch: how contact varies when
// the upper jaw is shifted along the anterior axis (z in L) from its designed bite, and which
// seats the planner's local search finds from starts at the promising shifts.
//
//   occlude_synthetic_basins [triangles=20000] [seed=1] [starts=4] [range_mm=12] [step_mm=0.5]
//
// 1. Sweep: the upper moved by dz along z (anterior) from X_LU, then settled along the occlusal
//    axis (y) to the penetration limit (the largest closing whose outlier-robust penetration is
//    within the request's limit, by bisection); contact area on the 0.4 mm sub-voxel oracle.
// 2. Candidates: dz = 0 and every local maximum of the settled contact area.
// 3. Searches: planner::Plan (coarse-to-fine, 0.8 then 0.4 mm, bounds +-3 mm / +-5 deg, one
//    start) from each candidate's settled pose and from `starts - 1` seeded perturbations of it
//    (up to 1 mm and 2 deg about the occlusal pivot).
// 4. Seats: the found poses clustered (within 0.5 mm at the arch reference points and 1 deg),
//    with their shift from the designed bite, contact and penetration, and where their starts
//    came from. Times are thread CPU seconds.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "occlude/io/dental.h"
#include "occlude/io/synthetic_jaws.h"
#include "occlude/planner/evaluation.h"
#include "occlude/planner/plan.h"

using namespace occlude;

namespace {

constexpr double kSeatTranslationMm = 0.5;  // one seat: within this at the reference points
constexpr double kSeatRotationDeg = 1.0;    // ... and this relative rotation
constexpr double kStartJitterMm = 1.0;      // perturbed starts: up to this far
constexpr double kStartJitterDeg = 2.0;     // ... and this rotation about the pivot
constexpr double kMaxOpeningMm = 12.0;      // the settle opens at most this far
constexpr int kSettleIterations = 40;       // bisection steps (24 mm / 2^40)

double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Setup {
  io::SyntheticJawPair pair;
  planner::OwnedSchedule schedule;  // 0.8 then 0.4 mm sub-voxel
  std::vector<Eigen::Vector3d> points_U;
  Eigen::Vector3d pivot_L;
  planner::PlanRequest request;  // band, limit and measure of `propose`
  const planner::OracleStage& fine() const { return schedule.stages.back(); }
};

/// A pose and what the fine oracle says of it.
struct Seat {
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
  planner::PoseEvaluation evaluation;
  double closing_mm = 0.0;  // settle: > 0 moved towards the lower jaw
};

/// X moved by c along the closing direction (-occlusal axis, y in L).
Eigen::Isometry3d Closed(const Eigen::Isometry3d& X, const Eigen::Vector3d& occlusal_L, double c) {
  Eigen::Isometry3d Y = X;
  Y.pretranslate(-c * occlusal_L);
  return Y;
}

/// The largest closing within [-kMaxOpeningMm, kMaxOpeningMm] that keeps X feasible.
Seat Settle(const Setup& s, const Eigen::Isometry3d& X) {
  const Eigen::Vector3d axis = s.pair.occlusal_axis_L;
  const auto feasible = [&](double c) {
    return planner::EvaluatePose(s.fine(), Closed(X, axis, c), s.request).feasible;
  };
  double open = -kMaxOpeningMm, shut = kMaxOpeningMm;  // open feasible, shut not (assumed)
  for (int k = 0; k < kSettleIterations; ++k) {
    const double mid = 0.5 * (open + shut);
    (feasible(mid) ? open : shut) = mid;
  }
  Seat seat;
  seat.closing_mm = open;
  seat.X_LU = Closed(X, axis, open);
  seat.evaluation = planner::EvaluatePose(s.fine(), seat.X_LU, s.request);
  return seat;
}

Setup MakeSetup(std::size_t triangles, std::uint32_t seed) {
  Setup s;
  io::SyntheticJawOptions options;
  options.triangles_per_jaw = triangles;
  options.seed = seed;
  s.pair = io::MakeSyntheticJawPair(options);
  auto lower = std::make_shared<io::TriangleMesh>(s.pair.lower_L);
  auto upper = std::make_shared<io::TriangleMesh>(s.pair.upper_U);
  s.schedule = planner::BuildSchedule(lower, upper, {0.8, 0.4}, false);
  s.points_U = planner::ArchReferencePoints_U(*upper, s.pair.X_LU, s.fine().oracle->arch());
  s.pivot_L = s.pair.X_LU * s.points_U[0];
  return s;
}

/// Displacement of the occlusal pivot from the designed bite (L), mm.
Eigen::Vector3d ShiftOf(const Setup& s, const Eigen::Isometry3d& X_LU) {
  return X_LU * s.points_U[0] - s.pair.X_LU * s.points_U[0];
}

struct SweepRow {
  double dz = 0.0;
  Seat seat;
};

std::vector<SweepRow> Sweep(const Setup& s, double range, double step) {
  std::printf("\nsweep: upper shifted by dz along z (anterior) from the designed bite, settled\n");
  std::printf("along y to the penetration limit (%.2f mm robust), 0.4 mm sub-voxel\n",
              s.request.max_penetration_mm);
  std::printf("  dz_mm  closing_mm  contact_mm2  post_L_mm2  post_R_mm2  maxpen_mm  robust_mm\n");
  std::vector<SweepRow> rows;
  const int n = static_cast<int>(std::lround(range / step));
  for (int k = -n; k <= n; ++k) {
    SweepRow row;
    row.dz = k * step;
    row.seat = Settle(s, Eigen::Translation3d(0.0, 0.0, row.dz) * s.pair.X_LU);
    const planner::PoseEvaluation& e = row.seat.evaluation;
    std::printf("%7.2f  %10.3f  %11.2f  %10.2f  %10.2f  %9.3f  %9.3f\n", row.dz,
                row.seat.closing_mm, e.contact_area_mm2, e.posterior_left_mm2,
                e.posterior_right_mm2, e.max_penetration_mm, e.constrained_penetration_mm);
    std::fflush(stdout);
    rows.push_back(row);
  }
  return rows;
}

/// dz = 0 and the strict local maxima of the settled contact area (plateaus count once).
std::vector<std::size_t> Candidates(const std::vector<SweepRow>& rows) {
  std::vector<std::size_t> picks;
  const auto area = [&](std::size_t k) { return rows[k].seat.evaluation.contact_area_mm2; };
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const bool zero = std::abs(rows[k].dz) < 1e-9;
    const bool left_lower = k == 0 || area(k - 1) < area(k);
    const bool right_not_higher = k + 1 == rows.size() || area(k + 1) <= area(k);
    if (zero || (area(k) > 0.0 && left_lower && right_not_higher)) picks.push_back(k);
  }
  return picks;
}

struct Search {
  std::size_t candidate = 0;  // index into the candidate list
  int start = 0;
  planner::Proposal found;
  double cpu_seconds = 0.0;
};

/// Uniform in [-1, 1) from the standard mt19937 stream (the same with every library).
double Draw(std::mt19937& rng) { return static_cast<double>(rng()) / 2147483648.0 - 1.0; }

Eigen::Isometry3d Perturbed(const Setup& s, const Eigen::Isometry3d& X, std::mt19937& rng) {
  planner::PoseParameters p;
  for (int i = 0; i < 3; ++i) p.translation_mm[i] = kStartJitterMm / std::sqrt(3.0) * Draw(rng);
  for (int i = 0; i < 3; ++i) p.rotation_deg[i] = kStartJitterDeg / std::sqrt(3.0) * Draw(rng);
  const Eigen::Vector3d pivot_at_X = X * s.points_U[0];
  return planner::ComposePose(p, pivot_at_X, X);
}

Search RunSearch(const Setup& s, const Eigen::Isometry3d& start, std::uint32_t seed) {
  planner::PlanRequest request = s.request;
  request.solver = planner::SolverKind::kCoarseToFine;
  request.X_LU_start = start;
  request.num_starts = 1;
  request.num_threads = 1;
  request.max_proposals = 1;
  request.seed = seed;
  request.lower_bound = {Eigen::Vector3d::Constant(-3.0), Eigen::Vector3d::Constant(-5.0)};
  request.upper_bound = {Eigen::Vector3d::Constant(3.0), Eigen::Vector3d::Constant(5.0)};
  Search search;
  const double t0 = ThreadCpuSeconds();
  search.found = planner::Plan(s.schedule.stages, request).proposals.front();
  search.cpu_seconds = ThreadCpuSeconds() - t0;
  return search;
}

std::vector<Search> Searches(const Setup& s, const std::vector<SweepRow>& rows,
                             const std::vector<std::size_t>& candidates, int starts) {
  std::printf(
      "\nsearches: coarse-to-fine (0.8, 0.4 mm), bounds +-3 mm / +-5 deg, one start each\n");
  std::printf(
      " cand  cand_dz  start  dz_mm   dx_mm   dy_mm  rot_deg  contact_mm2  maxpen  robust"
      "  status          cpu_s\n");
  std::vector<Search> all;
  std::mt19937 rng(20261203u);
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const SweepRow& row = rows[candidates[c]];
    for (int k = 0; k < starts; ++k) {
      const Eigen::Isometry3d start = k == 0 ? row.seat.X_LU : Perturbed(s, row.seat.X_LU, rng);
      Search search = RunSearch(s, start, static_cast<std::uint32_t>(1 + all.size()));
      search.candidate = c;
      search.start = k;
      const planner::Proposal& f = search.found;
      const Eigen::Vector3d d = ShiftOf(s, f.X_LU);
      const double rot = planner::ComparePoses(f.X_LU, s.pair.X_LU, s.points_U).rotation_deg;
      std::printf(
          "%5zu  %7.2f  %5d  %6.2f  %6.2f  %6.2f  %7.2f  %11.2f  %6.3f  %6.3f  %-14s  %5.2f\n", c,
          row.dz, k, d.z(), d.x(), d.y(), rot, f.evaluation.contact_area_mm2,
          f.evaluation.max_penetration_mm, f.evaluation.constrained_penetration_mm,
          planner::ToString(f.status), search.cpu_seconds);
      std::fflush(stdout);
      all.push_back(search);
    }
  }
  return all;
}

struct Cluster {
  std::vector<std::size_t> members;  // indices into the searches; the first is the anchor
  std::size_t best = 0;              // the feasible member with the most contact (else the anchor)
};

/// Greedy clustering: a search joins the first cluster whose anchor is within the seat bar.
std::vector<Cluster> ClusterSeats(const Setup& s, const std::vector<Search>& searches) {
  std::vector<Cluster> clusters;
  const auto area = [&](std::size_t i) { return searches[i].found.evaluation.contact_area_mm2; };
  const auto feasible = [&](std::size_t i) { return searches[i].found.evaluation.feasible; };
  for (std::size_t k = 0; k < searches.size(); ++k) {
    const Eigen::Isometry3d& X = searches[k].found.X_LU;
    Cluster* home = nullptr;
    for (Cluster& c : clusters) {
      const planner::PoseError e =
          planner::ComparePoses(X, searches[c.members.front()].found.X_LU, s.points_U);
      if (e.translation_mm <= kSeatTranslationMm && e.rotation_deg <= kSeatRotationDeg) home = &c;
      if (home) break;
    }
    if (!home) home = &clusters.emplace_back(Cluster{{}, k});
    home->members.push_back(k);
    const std::size_t b = home->best;
    if (feasible(k) && (!feasible(b) || area(k) > area(b))) home->best = k;
  }
  std::sort(clusters.begin(), clusters.end(), [&](const Cluster& a, const Cluster& b) {
    return ShiftOf(s, searches[a.best].found.X_LU).z() <
           ShiftOf(s, searches[b.best].found.X_LU).z();
  });
  return clusters;
}

/// Contact per upper tooth (FDI number: mm^2), teeth with at least 0.05 mm^2.
void PrintTeeth(const planner::PoseEvaluation& e) {
  std::printf("        by upper tooth:");
  for (const collision::PartTotals& part : e.parts) {
    if (part.tooth_number <= 0 || part.contact_area_mm2 < 0.05) continue;
    std::printf(" %d: %.1f", io::FdiFromUniversal(part.tooth_number), part.contact_area_mm2);
  }
  std::printf("\n");
}

void PrintSeats(const Setup& s, const std::vector<SweepRow>& rows,
                const std::vector<std::size_t>& candidates, const std::vector<Search>& searches) {
  const std::vector<Cluster> clusters = ClusterSeats(s, searches);
  const Seat design = Settle(s, s.pair.X_LU);
  const double design_area = design.evaluation.contact_area_mm2;
  std::printf(
      "\nseats (searches within %.1f mm / %.0f deg of each other); designed bite settled: "
      "%.2f mm2, closing %.3f mm\n",
      kSeatTranslationMm, kSeatRotationDeg, design_area, design.closing_mm);
  PrintTeeth(design.evaluation);
  std::printf(
      " seat  dz_mm   dx_mm   dy_mm  rot_deg  contact_mm2  of_design  post_L  post_R  maxpen"
      "  robust  starts  from candidates (dz: count)\n");
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const planner::PoseEvaluation& e = searches[clusters[c].best].found.evaluation;
    const Eigen::Isometry3d& X = searches[clusters[c].best].found.X_LU;
    const Eigen::Vector3d d = ShiftOf(s, X);
    const double rot = planner::ComparePoses(X, s.pair.X_LU, s.points_U).rotation_deg;
    std::printf(
        "%5zu  %5.2f  %6.2f  %6.2f  %7.2f  %11.2f  %8.0f%%  %6.2f  %6.2f  %6.3f  %6.3f  %6zu  ", c,
        d.z(), d.x(), d.y(), rot, e.contact_area_mm2, 100.0 * e.contact_area_mm2 / design_area,
        e.posterior_left_mm2, e.posterior_right_mm2, e.max_penetration_mm,
        e.constrained_penetration_mm, clusters[c].members.size());
    for (std::size_t cand = 0; cand < candidates.size(); ++cand) {
      int count = 0;
      for (const std::size_t m : clusters[c].members) count += searches[m].candidate == cand;
      if (count > 0) std::printf(" %.1f: %d", rows[candidates[cand]].dz, count);
    }
    std::printf("\n");
    if (e.contact_area_mm2 >= 0.25 * design_area) PrintTeeth(e);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const auto arg = [&](int i, double fallback) { return argc > i ? std::atof(argv[i]) : fallback; };
  const auto triangles = static_cast<std::size_t>(arg(1, 20000));
  const auto seed = static_cast<std::uint32_t>(arg(2, 1));
  const int starts = std::max(1, static_cast<int>(arg(3, 4)));
  const double range = arg(4, 12.0), step = arg(5, 0.5);
  try {
    const double t0 = ThreadCpuSeconds();
    const Setup s = MakeSetup(triangles, seed);
    std::printf(
        "synthetic pair: %zu triangles per jaw, seed %u; %zu designed contacts; oracles "
        "built in %.1f s CPU\n",
        triangles, seed, s.pair.contacts.size(), ThreadCpuSeconds() - t0);
    const std::vector<SweepRow> rows = Sweep(s, range, step);
    const std::vector<std::size_t> candidates = Candidates(rows);
    std::printf("\ncandidates (dz mm):");
    for (const std::size_t k : candidates) std::printf(" %.1f", rows[k].dz);
    std::printf("\n");
    const std::vector<Search> searches = Searches(s, rows, candidates, starts);
    PrintSeats(s, rows, candidates, searches);
    std::printf("\ntotal %.1f s CPU\n", ThreadCpuSeconds() - t0);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "occlude_synthetic_basins: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
