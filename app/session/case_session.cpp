// A case's models, built once (see case_session.h).
#include "session/case_session.h"

#include <algorithm>
#include <iostream>
#include <sstream>
#include <stdexcept>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "base/tasks.h"
#include "base/user_error.h"
#include "occlude/collision/arch_frame.h"
#include "occlude/collision/region_of_interest.h"
#include "occlude/collision/voxel_grid.h"
#include "session/jaw_checks.h"
#include "session/memory_guard.h"
#include "session/region_entry.h"

namespace occlude::app {
namespace {

// The map fields use coarse voxels: Exact() is exact at any voxel size, and a coarse grid
// keeps the search for a 1 mm reach to a few voxels per vertex. Exact-only fields: no corner
// values.
constexpr double kMapVoxelMm = 0.4;

// A region keeping at least this share of a jaw's triangles is not worth a cut (session_region.h).
constexpr double kWholeAboveShare = 0.95;

// glibc keeps freed blocks in its arenas for reuse (its mmap threshold grows past the oracles'
// arrays once large blocks were freed): hands the freed pages back to the system, so that what
// a build or a released oracle freed does not stay resident.
void ReturnFreedMemory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

collision::NarrowBandSdf MapField(std::shared_ptr<const io::TriangleMesh> mesh) {
  collision::VoxelizeOptions options;
  options.voxel_size_mm = kMapVoxelMm;
  options.classify_proximity = false;
  options.classify_interior = false;
  const collision::VoxelGrid grid = collision::Voxelize(*mesh, options);
  collision::NarrowBandOptions band;
  band.dilation_voxels = 0;
  band.corner_values = false;  // the maps ask Exact() only
  return collision::NarrowBandSdf::Build(std::move(mesh), grid, band);
}

std::string Mm(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

collision::ArchFrame CaseArchFrame(const CaseConfig& config, const io::TriangleMesh& lower_L,
                                   const io::TriangleMesh& upper_U, const Eigen::Isometry3d& X_LU) {
  collision::ArchFrame f = collision::EstimateArchFrame(lower_L, upper_U.Transformed(X_LU));
  if (!config.up_axis_L) return f;
  const Eigen::Vector3d up = *config.up_axis_L;
  Eigen::Vector3d anterior = f.anterior_L - f.anterior_L.dot(up) * up;
  if (anterior.norm() < 1e-6) anterior = up.unitOrthogonal();
  f.occlusal_L = up;
  f.anterior_L = anterior.normalized();
  f.lateral_L = f.occlusal_L.cross(f.anterior_L).normalized();
  return f;
}

std::vector<double> ScheduleVoxels(double finest_mm) {
  if (finest_mm < 0.4) return {0.8, 0.4, finest_mm};
  return {std::max(0.8, 2.0 * finest_mm), finest_mm};
}

std::vector<double> ScheduleVoxels(const CaseConfig& config) {
  return ScheduleVoxels(config.VoxelSizeMm());
}

namespace {

// The options every oracle of a session shares before its stage's: the config's sample spacing,
// and none of the structures only queries between the two trees read (a session asks the
// oracle alone).
collision::OracleOptions SessionOracleBase(const CaseConfig& config) {
  collision::OracleOptions base;
  base.sample_spacing_mm = config.sample_spacing_mm;
  base.tree_queries = false;
  return base;
}

}  // namespace

collision::MemoryEstimate EstimateSessionMemory(const CaseConfig& config, const JawPair& jaws,
                                                double voxel_mm) {
  // (The config's voxel size is its resolution choice; the guard asks about others.)
  const std::vector<double> voxels = ScheduleVoxels(voxel_mm);
  const collision::OracleOptions base = SessionOracleBase(config);
  collision::MemoryEstimate total;
  for (std::size_t i = 0; i < voxels.size(); ++i) {
    total += collision::EstimateOracleMemory(*jaws.lower_L, *jaws.upper_U,
                                             planner::StageOracleOptions(base, voxels, i));
  }
  total += collision::EstimateNarrowBandSdfMemory(*jaws.lower_L, kMapVoxelMm, 0);
  total += collision::EstimateNarrowBandSdfMemory(*jaws.upper_U, kMapVoxelMm, 0);
  return total;
}

namespace {

// The files of a jaw for messages.
std::string JawName(const CaseConfig& config, const std::optional<JawFiles>& jaw) {
  if (!jaw) return config.file.string() + " [synthetic]";
  std::vector<std::string> files;
  for (const auto& f : jaw->files) files.push_back(f.string());
  return JawFilesName(files);
}

}  // namespace

CaseSession::CaseSession(const CaseConfig& config, double memory_budget_mb)
    : config_(config),
      cache_(std::make_shared<OracleCache>(
          OracleCacheSettings{config.cache_enabled, config.cache_folder, config.cache_mb},
          &std::cerr)) {
  StepClock clock;
  clock.Start("loaded the meshes");
  JawPair loaded = LoadConfigJaws(config_);
  X_LU_ref_loaded_ = loaded.X_LU_ref;
  jaws_ = AtReference(std::move(loaded));
  clock.Finish();
  ReadGiven();
  const std::string lower_name = JawName(config_, config_.lower),
                    upper_name = JawName(config_, config_.upper);
  for (const std::string& w : JawPairWarnings(
           *jaws_.lower_L, *jaws_.upper_U, Eigen::Isometry3d::Identity(), lower_name, upper_name)) {
    std::cerr << "occlude: warning: " << w << "\n";
  }
  // The memory check and the arch frame read the meshes alone: both at once (the check's error,
  // if any, first).
  RunTasks({[&] {
              CheckMemory(
                  {config_.file.string(),
                   "the contact oracles and the map fields",
                   "accuracy.voxel_mm",
                   5.0,
                   "decimate the meshes or raise accuracy.sample_spacing_mm",
                   {ExtentOf(lower_name, *jaws_.lower_L), ExtentOf(upper_name, *jaws_.upper_U)}},
                  [&](double voxel_mm) { return EstimateSessionMemory(config_, jaws_, voxel_mm); },
                  config_.VoxelSizeMm(),
                  ResolveMemoryBudget(memory_budget_mb, config_.memory_budget_mb));
            },
            [&] {
              StepClock arch_clock;
              arch_clock.Start("estimated the arch frame");
              arch_ = CaseArchFrame(config_, *jaws_.lower_L, *jaws_.upper_U,
                                    Eigen::Isometry3d::Identity());
              pivot_L_ = config_.start.pivot_mm.value_or(collision::UpperOcclusalCentre(
                  *jaws_.upper_U, Eigen::Isometry3d::Identity(), arch_.occlusal_L));
            }});
  std::cerr << "occlude: " << config_.resolution.Describe() << "\n";
}

void CaseSession::UseArchFrame(const collision::ArchFrame& arch) {
  if (!models_.empty())
    throw std::logic_error("CaseSession::UseArchFrame after an oracle was built");
  arch_ = arch;
}

Eigen::Isometry3d CaseSession::ConfigStartPose() const { return StartPoseOf(config_, pivot_L_); }

std::unique_ptr<collision::JawOracle> CaseSession::BuildOracle(
    std::shared_ptr<const io::TriangleMesh> lower_L,
    std::shared_ptr<const io::TriangleMesh> upper_U, const collision::OracleOptions& options,
    const std::string& what) {
  StepClock clock;
  clock.Start("built the " + Mm(options.voxel_size_mm) + " mm contact oracle" + what);
  try {
    return cache_->Get(lower_L, upper_U, options, [&] {
      *built_oracles_ = true;
      auto built = std::make_unique<collision::JawOracle>(lower_L, upper_U, options);
      ReturnFreedMemory();  // the build's transient grids, before the next build or the save
      return built;
    });
  } catch (const collision::VoxelizeError& e) {
    throw UserError(config_.file.string() + ": accuracy: " + e.what());
  }
}

collision::RegionOfInterestRequest CaseSession::RegionRequest(double band_mm) const {
  const Eigen::Isometry3d X_start = ConfigStartPose();
  return SessionRegionRequest(config_, X_start, X_start * pivot_L_, band_mm);
}

collision::RegionOfInterest CaseSession::SelectRegion(double band_mm, double* selector_seconds) {
  // A warm run reads the selection (a few bytes when a jaw is kept whole) instead of making the
  // jaws' distance bounds again; either way the same sub-meshes, so the same oracle keys.
  return MadeOrCached(
      cache_.get(), kRegionEntryKind,
      [&] {
        return RegionEntryKey(cache_->MeshHash(jaws_.lower_L), cache_->MeshHash(jaws_.upper_U),
                              RegionRequest(band_mm));
      },
      [&] {
        if (!region_) {
          region_ = std::make_unique<collision::RegionSelector>(jaws_.lower_L, jaws_.upper_U,
                                                                RegionRequest(0.0));
          *selector_seconds = region_->seconds();
        }
        return region_->Select(band_mm);
      },
      EncodeRegion,
      [&](std::string_view bytes) { return DecodeRegion(bytes, jaws_.lower_L, jaws_.upper_U); });
}

CaseSession::StageInputs CaseSession::PrepareStage(std::size_t index) {
  collision::OracleOptions base = SessionOracleBase(config_);
  base.arch = arch_;
  StageInputs in;
  in.options = planner::StageOracleOptions(base, ScheduleVoxels(config_), index);
  in.model = {in.options.voxel_size_mm, std::nullopt, 0, 0.0};
  in.lower = jaws_.lower_L;
  in.upper = jaws_.upper_U;
  if (!config_.region_of_interest) return in;
  double selector_seconds = 0.0;  // the bounds' share, counted with the first region made
  const collision::RegionOfInterest roi =
      SelectRegion(SessionReadRadiusMm(config_, in.options), &selector_seconds);
  // A jaw that keeps nearly everything is modelled whole (the cut would save little and cost a
  // copy of the mesh), and so is one that keeps nothing (jaws out of each other's reach: an
  // oracle needs a surface).
  auto pick = [](const collision::RegionMesh& sub,
                 const std::shared_ptr<const io::TriangleMesh>& whole) {
    const auto kept = static_cast<double>(sub.mesh->num_triangles());
    return sub.mesh->empty() ||
                   kept >= kWholeAboveShare * static_cast<double>(whole->num_triangles())
               ? whole
               : sub.mesh;
  };
  in.lower = pick(roi.lower, jaws_.lower_L);
  in.upper = pick(roi.upper, jaws_.upper_U);
  in.model.lower_cut = in.lower != jaws_.lower_L;
  in.model.upper_cut = in.upper != jaws_.upper_U;
  std::cerr << "occlude: " << RegionLine(in.options.voxel_size_mm, roi.stats)
            << (in.model.lower_cut || in.model.upper_cut
                    ? ""
                    : "; too little to cut: modelling the whole jaws")
            << "\n";
  in.what = " on the region of interest";
  in.model.region = roi.stats;
  in.model.build_seconds = selector_seconds + roi.stats.seconds;
  return in;
}

std::unique_ptr<collision::JawOracle> CaseSession::BuildStage(const StageInputs& in) {
  return BuildOracle(in.lower, in.upper, in.options, in.what);
}

void CaseSession::KeepStage(std::size_t index, StageInputs in,
                            std::unique_ptr<collision::JawOracle> oracle) {
  in.model.bytes = oracle->MemoryBytes();
  in.model.build_seconds += oracle->build_seconds();
  models_.push_back(in.model);
  oracles_[index] = std::move(oracle);
}

const collision::JawOracle& CaseSession::Oracle(std::size_t index) {
  if (oracles_.empty()) oracles_.resize(ScheduleVoxels(config_).size());
  if (!oracles_[index]) {
    StageInputs in = PrepareStage(index);
    std::unique_ptr<collision::JawOracle> oracle = BuildStage(in);
    KeepStage(index, std::move(in), std::move(oracle));
  }
  return *oracles_[index];
}

const planner::OracleSchedule& CaseSession::Schedule() {
  if (stages_.empty()) {
    const std::size_t n = ScheduleVoxels(config_).size();
    if (oracles_.empty()) oracles_.resize(n);
    // The stages the cache holds are read at once (reading is copying and checking, on one
    // core each); the others are built one after the other, as a build uses every core and
    // its transient grids would add up.
    std::vector<StageInputs> inputs(n);
    std::vector<std::unique_ptr<collision::JawOracle>> made(n);
    std::vector<std::function<void()>> reads;
    for (std::size_t i = 0; i < n; ++i) {
      if (oracles_[i]) continue;
      inputs[i] = PrepareStage(i);
      if (cache_->Holds(inputs[i].lower, inputs[i].upper, inputs[i].options))
        reads.emplace_back([&, i] { made[i] = BuildStage(inputs[i]); });
    }
    // The finest (largest) first: the longest read starts at once, the others share the other
    // core (a-bite: 132 MB against 59 + 39 MB).
    std::reverse(reads.begin(), reads.end());
    RunTasks(reads);
    for (std::size_t i = 0; i < n; ++i) {
      if (oracles_[i]) continue;
      if (!made[i]) made[i] = BuildStage(inputs[i]);
      KeepStage(i, std::move(inputs[i]), std::move(made[i]));
    }
    // Coarse stages at sub-voxel level; the finest at the level chosen for the accuracy.
    for (std::size_t i = 0; i < n; ++i) {
      stages_.push_back(
          {&Oracle(i), i + 1 == n ? config_.OracleLevel() : collision::AccuracyLevel::kSubVoxel});
    }
    // What the last save and the loads freed, before the search (a cold run's peak memory).
    ReturnFreedMemory();
  }
  return stages_;
}

void CaseSession::ReleaseCoarseOracles() {
  stages_.clear();
  for (std::size_t i = 0; i + 1 < oracles_.size(); ++i) oracles_[i].reset();
  ReturnFreedMemory();
}

const collision::JawOracle& CaseSession::FinestOracle() {
  const std::size_t last = ScheduleVoxels(config_).size() - 1;
  if (!config_.region_of_interest) return Oracle(last);
  // The schedule's finest is that oracle when the region kept the whole jaws.
  const collision::JawOracle* scheduled = BuiltScheduledFinest();
  if (!whole_finest_ && scheduled != nullptr &&
      &scheduled->lower_tree().mesh() == jaws_.lower_L.get() &&
      &scheduled->upper_tree().mesh() == jaws_.upper_U.get()) {
    return *scheduled;
  }
  if (!whole_finest_) {
    collision::OracleOptions base = SessionOracleBase(config_);
    base.arch = arch_;
    const collision::OracleOptions options =
        planner::StageOracleOptions(base, ScheduleVoxels(config_), last);
    whole_finest_ = BuildOracle(jaws_.lower_L, jaws_.upper_U, options, " on the whole jaws");
    models_.push_back({options.voxel_size_mm, std::nullopt, whole_finest_->MemoryBytes(),
                       whole_finest_->build_seconds()});
  }
  return *whole_finest_;
}

const collision::JawOracle& CaseSession::FinestOracleAt(const Eigen::Isometry3d& X_LU) {
  if (!config_.region_of_interest || whole_finest_) return FinestOracle();
  const double displacement = collision::MaxDisplacementMm(*jaws_.upper_U, RegionRequest(0.0));
  if (collision::RegionCoversPose(*jaws_.upper_U, ConfigStartPose(), X_LU, displacement)) {
    return Oracle(ScheduleVoxels(config_).size() - 1);
  }
  return FinestOracle();
}

const MapFields& CaseSession::Maps() {
  if (!maps_) {
    StepClock clock;
    clock.Start("built the distance fields of the maps");
    maps_ = std::make_unique<MapFields>();
    maps_->shared_lower = WholeLowerField();
    if (maps_->shared_lower == nullptr) maps_->own_lower = MapField(jaws_.lower_L);
    maps_->own_upper = upper_map_.valid() ? upper_map_.get() : MapField(jaws_.upper_U);
  }
  const double reach = MapReachMm(config_);
  if (maps_->lower_near.reach_mm() != reach) {
    RunTasks({[&] { maps_->lower_near = NearCells(*jaws_.lower_L, reach); },
              [&] { maps_->upper_near = NearCells(*jaws_.upper_U, reach); }});
  }
  return *maps_;
}

const collision::JawOracle* CaseSession::BuiltScheduledFinest() const {
  const std::size_t last = ScheduleVoxels(config_).size() - 1;
  return last < oracles_.size() ? oracles_[last].get() : nullptr;
}

const collision::NarrowBandSdf* CaseSession::WholeLowerField() const {
  // Built oracles only (building one for this would cost more than the map field), the finest
  // first: it is never released.
  const collision::JawOracle* whole = whole_finest_.get();
  for (const collision::JawOracle* o : {whole, BuiltScheduledFinest()}) {
    if (o != nullptr && &o->lower_tree().mesh() == jaws_.lower_L.get()) return &o->lower_sdf();
  }
  return nullptr;
}

namespace {

// The inputs of a session's region of interest besides the models' (start pose, bounds, locks,
// the bands: session_region.h).
bool SameRegionInputs(const CaseConfig& a, const CaseConfig& b) {
  for (std::size_t d = 0; d < kNumDofs; ++d) {
    if (a.bounds[d].min != b.bounds[d].min || a.bounds[d].max != b.bounds[d].max) return false;
  }
  return a.locked == b.locked && a.start.matrix == b.start.matrix &&
         a.start.params.translation_mm == b.start.params.translation_mm &&
         a.start.params.rotation_deg == b.start.params.rotation_deg &&
         a.contact_band_mm == b.contact_band_mm && a.max_penetration_mm == b.max_penetration_mm &&
         a.report.map_max_mm == b.report.map_max_mm;
}

}  // namespace

void CaseSession::ReadGiven() {
  given_.clear();
  if (config_.landmarks_file) {
    given_ = GivenAtReference(X_LU_ref_loaded_, ReadGivenLandmarks(*config_.landmarks_file));
  }
}

void CaseSession::UpdateSettings(const CaseConfig& other) {
  if (!SameRegionInputs(config_, other)) region_.reset();
  config_ = other;
  ReadGiven();
  analysis_.reset();
}

void CaseSession::Prefetch() {
  // The threads hold the meshes (shared): the session may move while they run.
  if (!detected_ && !detecting_.valid()) {
    detecting_ = std::async(std::launch::async, [jaws = jaws_, cache = cache_] {
      return AnalyzeCase(jaws, {}, cache.get());
    });
  }
  if (!maps_ && !upper_map_.valid()) {
    upper_map_ =
        std::async(std::launch::async, [upper = jaws_.upper_U] { return MapField(upper); });
  }
}

const CaseAnalysis& CaseSession::Analysis() {
  if (analysis_) return *analysis_;
  if (!detected_ && detecting_.valid()) {
    detected_ = std::make_unique<CaseAnalysis>(detecting_.get());
  } else if (!detected_) {
    StepClock clock;
    clock.Start("analysed both arches");
    detected_ = std::make_unique<CaseAnalysis>(AnalyzeCase(jaws_, {}, cache_.get()));
  }
  analysis_ = std::make_unique<CaseAnalysis>(*detected_);
  analysis::ApplyGivenLandmarks(given_, &analysis_->lower_L);
  analysis::ApplyGivenLandmarks(given_, &analysis_->upper_U);
  analysis_->has_given_landmarks = !given_.empty();
  return *analysis_;
}

bool CaseSession::Reusable(const CaseConfig& other) const {
  auto same_files = [](const std::optional<JawFiles>& a, const std::optional<JawFiles>& b) {
    if (a.has_value() != b.has_value()) return false;
    return !a || (a->files == b->files && a->parts == b->parts);
  };
  const bool same_synthetic =
      config_.synthetic.has_value() == other.synthetic.has_value() &&
      (!config_.synthetic || (config_.synthetic->triangles == other.synthetic->triangles &&
                              config_.synthetic->seed == other.synthetic->seed));
  return same_files(config_.lower, other.lower) && same_files(config_.upper, other.upper) &&
         same_synthetic && config_.units == other.units && config_.up_axis_L == other.up_axis_L &&
         ScheduleVoxels(config_) == ScheduleVoxels(other) &&
         config_.sample_spacing_mm == other.sample_spacing_mm &&
         config_.start.pivot_mm == other.start.pivot_mm &&
         config_.region_of_interest == other.region_of_interest &&
         (!config_.region_of_interest || oracles_.empty() || SameRegionInputs(config_, other));
}

}  // namespace occlude::app
