// Measures the global search on the synthetic pair or a case in
// registered occlusion: the seat of the reference (the local search from the
// reference pose), then from seeded starts of each kind the global search and
// whether its proposals find that seat. A start is the upper mesh as a file
// would bring it (in L at the start pose: the oracles are built again on it),
// with a stand-in arch analysis of each jaw in its own file frame (tooth tops
// of the synthetic pair's and a-bite's tooth parts, or the c-cases' hand-
// placed landmarks; JawArchFromTeeth):
//   sagittal: the reference shifted along the arch by a uniform 3-12 mm either way plus up to
//             10 deg about a random axis (through the pivot);
//   apart:    the upper in a uniformly random orientation, 20-60 mm away;
//   reframe:  no global search: the seat of the reference again, with the upper in an apart
//             start's frame (its oracles rebuilt there): how far the seat itself moves with
//             the oracles' voxel grid, the floor under the errors of the other kinds;
//   noisy:    a sagittal start whose upper arch is off by what an arch analysis may miss: the
//             incisal point up to 2 mm in the occlusal plane, the axes up to 3 deg.
// Per start: top proposal within 0.3 mm / 1 deg of the seat (seat_success), the rank of the
// first proposal within the bar (seat_rank, 0: none), the errors, the thread CPU time of the
// search after the oracles are built and its phases. Then a summary per kind.
//
//   occlude_global_measure <case folder | synthetic> [starts=20] [kinds=sagittal,apart]
//                          [seed=1] [voxels=0.8,0.4] [threads=1] [verbose=0]
// (OCCLUDE_GLOBAL_BASINS=<max_basins>,<max_refined> overrides the scan's defaults 12,6.)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "occlude/angles.h"
#include "occlude/io/dental.h"
#include "occlude/io/landmark_file.h"
#include "occlude/io/mesh_io.h"
#include "occlude/io/synthetic_jaws.h"
#include "occlude/planner/global_search.h"
#include "occlude/planner/global_starts.h"
#include "session/jaw_pair.h"

using namespace occlude;

namespace {

constexpr double kBarMm = 0.3, kBarDeg = 1.0;

// Where a jaw's stand-in arch comes from: tooth parts of a mesh, or landmark tooth points.
struct ArchSource {
  io::TriangleMesh teeth_J;                   // parts with tooth numbers (may be empty)
  std::vector<planner::ToothPoint> points_J;  // else these
  Eigen::Vector3d occlusal_hint_J = Eigen::Vector3d::UnitY();

  planner::JawArch ArchIn(const Eigen::Isometry3d& X) const {  // the jaw moved by X
    const Eigen::Vector3d hint = X.linear() * occlusal_hint_J;
    if (!teeth_J.empty())
      return planner::JawArchFromTeeth(planner::ToothTops(teeth_J.Transformed(X), hint), hint);
    std::vector<planner::ToothPoint> moved = points_J;
    for (auto& t : moved) t.p_J = X * t.p_J;
    return planner::JawArchFromTeeth(moved, hint);
  }
};

struct Case {
  std::shared_ptr<const io::TriangleMesh> lower, upper;  // upper in U
  Eigen::Isometry3d X_true = Eigen::Isometry3d::Identity();
  ArchSource lower_arch, upper_arch;
};

// Landmark tooth points of one jaw: per tooth the mean of its cusp and incisal-edge landmarks.
std::vector<planner::ToothPoint> LandmarkTeeth(const std::vector<io::Landmark>& landmarks,
                                               io::Jaw jaw) {
  std::map<int, std::pair<Eigen::Vector3d, int>> sum;
  for (const io::Landmark& l : landmarks) {
    if (l.jaw != jaw || l.type == io::LandmarkType::kMesial ||
        l.type == io::LandmarkType::kDistal || l.type == io::LandmarkType::kFacial ||
        l.type == io::LandmarkType::kLingual || l.type == io::LandmarkType::kCentralFossa)
      continue;
    auto& [p, n] = sum.try_emplace(l.tooth_fdi, Eigen::Vector3d::Zero(), 0).first->second;
    p += l.p;
    ++n;
  }
  std::vector<planner::ToothPoint> teeth;
  for (const auto& [fdi, pn] : sum) teeth.push_back({fdi, pn.first / pn.second});
  return teeth;
}

// The part files Tooth_<first..last>.stl of a case's teeth/ folder, loaded as one jaw with tooth
// numbers (the session's part loader).
io::TriangleMesh TeethFiles(const std::filesystem::path& folder, int first, int last) {
  std::vector<std::filesystem::path> files;
  for (int n = first; n <= last; ++n) {
    const auto f = folder / ("Tooth_" + std::to_string(n) + ".stl");
    if (std::filesystem::exists(f)) files.push_back(f);
  }
  if (files.empty()) return {};
  return *app::LoadJaw(files, /*parts=*/true);
}

Case LoadCase(const std::string& which) {
  Case c;
  if (which == "synthetic") {
    const app::JawPair pair = app::SyntheticJawPair(20000, /*seed=*/1);
    c.lower = pair.lower_L;
    c.upper = pair.upper_U;
    c.X_true = pair.X_LU_ref;
    c.lower_arch.teeth_J = *pair.lower_L;
    c.upper_arch.teeth_J = *pair.upper_U;
    c.upper_arch.occlusal_hint_J = -Eigen::Vector3d::UnitY();  // the design: U parallel to L
    return c;
  }
  const std::filesystem::path dir = which;
  const app::JawPair jaws = app::LoadCaseFolder(dir);
  c.lower = jaws.lower_L;
  c.upper = jaws.upper_U;  // in L at the registered bite
  const Eigen::Vector3d up = collision::EstimateArchFrame(*c.lower, *c.upper).occlusal_L;
  c.lower_arch.occlusal_hint_J = up;
  c.upper_arch.occlusal_hint_J = -up;  // the cases share one frame at the registered bite
  if (std::filesystem::exists(dir / "landmarks.csv")) {
    const std::vector<io::Landmark> landmarks = io::ReadLandmarkFile(dir / "landmarks.csv");
    c.lower_arch.points_J = LandmarkTeeth(landmarks, io::Jaw::kLower);
    c.upper_arch.points_J = LandmarkTeeth(landmarks, io::Jaw::kUpper);
  } else {
    c.lower_arch.teeth_J = TeethFiles(dir / "teeth", 17, 32);
    c.upper_arch.teeth_J = TeethFiles(dir / "teeth", 1, 16);
  }
  return c;
}

// What the measurement knows of the reference.
struct Reference {
  const Case* c = nullptr;
  planner::JawArch lower_arch;
  planner::Proposal seat;
  std::vector<Eigen::Vector3d> points_U;
  Eigen::Vector3d pivot_L = Eigen::Vector3d::Zero();
  collision::OracleOptions base;
  std::vector<double> voxels;
  planner::PlanRequest local;
};

struct Outcome {
  bool success = false;
  int rank = 0;
  double err_mm = 0.0, err_deg = 0.0;
  planner::GlobalResult result;
};

// X_LU_file: the pose of U in the file frame of the upper as given (the frame the upper mesh,
// its arch and its oracles are in; the given pose of that frame in L is the identity).
Eigen::Isometry3d StartFrame(const Reference& ref, const std::string& kind, std::mt19937& rng) {
  if (kind == "apart" || kind == "reframe")
    return planner::ApartStart(ref.c->X_true, ref.pivot_L, rng);
  return planner::SagittalStart(ref.c->X_true, ref.pivot_L, ref.lower_arch.anterior_J, rng);
}

// The arch an analysis may find: the incisal point moved up to 2 mm in the occlusal plane,
// the axes turned by up to 3 deg about a random axis.
planner::JawArch Noisy(planner::JawArch a, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double angle = 2.0 * kPi * unit(rng), r = 2.0 * unit(rng);
  a.origin_J += r * (std::cos(angle) * a.lateral_J + std::sin(angle) * a.anterior_J);
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(RadiansFromDegrees(3.0 * unit(rng)), planner::RandomUnitVector(rng))
          .toRotationMatrix();
  a.occlusal_J = R * a.occlusal_J;
  a.anterior_J = R * a.anterior_J;
  a.lateral_J = R * a.lateral_J;
  return a;
}

Outcome RunStart(const Reference& ref, const std::string& kind, std::mt19937& rng) {
  const Eigen::Isometry3d X_file = StartFrame(ref, kind, rng);  // U -> the upper's file frame
  auto upper_file = std::make_shared<io::TriangleMesh>(ref.c->upper->Transformed(X_file));
  const planner::OwnedSchedule schedule =
      planner::BuildSchedule(ref.c->lower, upper_file, ref.voxels, false, ref.base);
  planner::GlobalRequest g;
  g.local = ref.local;
  g.lower_L = ref.lower_arch;
  g.upper_U = ref.c->upper_arch.ArchIn(X_file);
  if (const char* b = std::getenv("OCCLUDE_GLOBAL_BASINS"))  // max_basins,max_refined
    std::sscanf(b, "%d,%d", &g.scan.max_basins, &g.scan.max_refined);
  if (kind == "noisy") g.upper_U = Noisy(g.upper_U, rng);
  Outcome o;
  if (kind == "reframe") {
    planner::GlobalProposal seat;
    seat.proposal = planner::SeatOf(schedule.stages, ref.c->X_true * X_file.inverse(), ref.local);
    o.result.proposals.push_back(seat);
    o.result.cpu_seconds = seat.proposal.cpu_seconds;
  } else {
    o.result = planner::GlobalSearch(schedule.stages, g);
  }
  for (std::size_t k = 0; k < o.result.proposals.size(); ++k) {
    const planner::PoseError e = planner::ComparePoses(o.result.proposals[k].proposal.X_LU * X_file,
                                                       ref.seat.X_LU, ref.points_U);
    if (k == 0) {
      o.err_mm = e.translation_mm;
      o.err_deg = e.rotation_deg;
    }
    if (o.rank == 0 && e.translation_mm <= kBarMm && e.rotation_deg <= kBarDeg)
      o.rank = static_cast<int>(k) + 1;
  }
  o.success = o.rank == 1;
  return o;
}

void PrintResult(const planner::GlobalResult& r) {
  const auto& a = r.alignment;
  std::printf("  alignment: fit lateral %.2f anterior %.2f yaw %.2f deg, rms %.2f -> %.2f mm\n",
              a.fit_lateral_mm, a.fit_anterior_mm, a.fit_yaw_deg, a.fit_rms_before_mm,
              a.fit_rms_mm);
  for (const auto& w : r.warnings) std::printf("  warning: %s\n", w.c_str());
  for (std::size_t i = 0; i < r.basins.size(); ++i) {
    const auto& b = r.basins[i];
    std::printf(
        "  basin %2zu: sag %6.1f lat %5.1f yaw %5.1f pitch %5.1f  h %6.2f  cost %9.1f "
        "contact %6.2f\n",
        i, b.shift.sagittal_mm, b.shift.lateral_mm, b.shift.yaw_deg, b.shift.pitch_deg,
        b.shift.vertical_mm, b.seat_cost, b.contact_area_mm2);
  }
  for (std::size_t k = 0; k < r.proposals.size(); ++k) {
    const auto& p = r.proposals[k];
    std::printf(
        "  proposal %zu (basin %d): sag %6.2f lat %5.2f vert %5.2f yaw %5.2f pitch %5.2f "
        "roll %5.2f  seat_cost %9.1f contact %6.2f pen %.3f %s\n",
        k + 1, p.basin, p.from_aligned.sagittal_mm, p.from_aligned.lateral_mm,
        p.from_aligned.vertical_mm, p.from_aligned.yaw_deg, p.from_aligned.pitch_deg,
        p.from_aligned.roll_deg, p.proposal.seat_cost, p.proposal.evaluation.contact_area_mm2,
        p.proposal.evaluation.constrained_penetration_mm, planner::ToString(p.proposal.status));
  }
}

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void RunKind(const Reference& ref, const std::string& kind, int starts, std::uint32_t seed,
             bool verbose) {
  std::vector<double> cpu, scan, basins, refine, wall;
  int success = 0, among = 0;
  for (int run = 0; run < starts; ++run) {
    std::mt19937 rng(seed * 7919u + static_cast<unsigned>(run) * 104729u +
                     static_cast<unsigned>(kind.size()));
    const Outcome o = RunStart(ref, kind, rng);
    const planner::GlobalResult& r = o.result;
    success += o.success ? 1 : 0;
    among += o.rank > 0 ? 1 : 0;
    cpu.push_back(r.cpu_seconds);
    scan.push_back(r.scan_cpu_seconds);
    basins.push_back(r.basins_cpu_seconds);
    refine.push_back(r.refine_cpu_seconds);
    wall.push_back(r.wall_seconds);
    const double top_sag = r.proposals.empty() ? 0.0 : r.proposals[0].from_aligned.sagittal_mm;
    std::printf("%-9s %5d  %7d %4d  %6.3f %7.2f  %9zu %6zu %7.1f  %5.2f %5.2f %6.2f %6.2f %6.2f\n",
                kind.c_str(), run, o.success ? 1 : 0, o.rank, o.err_mm, o.err_deg,
                r.proposals.size(), r.basins.size(), top_sag, r.cpu_seconds, r.scan_cpu_seconds,
                r.basins_cpu_seconds, r.refine_cpu_seconds, r.wall_seconds);
    if (verbose) PrintResult(r);
    std::fflush(stdout);
  }
  std::printf(
      "summary %s: seat_success %d/%d, seat among the proposals %d/%d, median cpu %.2f s "
      "(scan %.2f, basins %.2f, refine %.2f), max cpu %.2f s, median wall %.2f s\n",
      kind.c_str(), success, starts, among, starts, Median(cpu), Median(scan), Median(basins),
      Median(refine), *std::max_element(cpu.begin(), cpu.end()), Median(wall));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s <case folder|synthetic> [starts=20] [kinds=sagittal,apart] [seed=1] "
                 "[voxels=0.8,0.4] [threads=1] [verbose=0]\n",
                 argv[0]);
    return 2;
  }
  const Case c = LoadCase(argv[1]);
  const int starts = argc > 2 ? std::max(1, std::atoi(argv[2])) : 20;
  const std::string kinds = argc > 3 ? argv[3] : "sagittal,apart";
  const auto seed = static_cast<std::uint32_t>(argc > 4 ? std::atoi(argv[4]) : 1);
  Reference ref;
  ref.c = &c;
  std::stringstream vs(argc > 5 ? argv[5] : "0.8,0.4");
  for (std::string tok; std::getline(vs, tok, ',');) ref.voxels.push_back(std::atof(tok.c_str()));
  ref.local.num_threads = argc > 6 ? std::atoi(argv[6]) : 1;
  ref.local.max_proposals = 8;
  const bool verbose = argc > 7 && std::atoi(argv[7]) != 0;
  ref.lower_arch = c.lower_arch.ArchIn(Eigen::Isometry3d::Identity());
  ref.base.arch = planner::FrameOf(ref.lower_arch);
  const planner::OwnedSchedule schedule =
      planner::BuildSchedule(c.lower, c.upper, ref.voxels, false, ref.base);
  ref.seat = planner::SeatOf(schedule.stages, c.X_true, ref.local);
  ref.points_U = planner::ArchReferencePoints_U(*c.upper, ref.seat.X_LU, *ref.base.arch);
  ref.pivot_L = c.X_true * ref.points_U[0];
  const planner::PoseError moved = planner::ComparePoses(ref.seat.X_LU, c.X_true, ref.points_U);
  std::printf("case %s, voxels %s, %d starts per kind, seed %u, threads %d\n", argv[1],
              argc > 5 ? argv[5] : "0.8,0.4", starts, seed, ref.local.num_threads);
  std::printf("seat of the reference: %.3f mm / %.2f deg from it, contact %.2f mm2, pen %.3f\n",
              moved.translation_mm, moved.rotation_deg, ref.seat.evaluation.contact_area_mm2,
              ref.seat.evaluation.constrained_penetration_mm);
  std::printf(
      "kind      start  success rank  err_mm err_deg  proposals basins top_sag  cpu_s  "
      "scan  basins refine wall_s\n");
  std::stringstream ks(kinds);
  for (std::string kind; std::getline(ks, kind, ',');) RunKind(ref, kind, starts, seed, verbose);
  return 0;
}
