// A case config turned into a planner request (see plan_config.h).
#include "config/plan_config.h"

#include <cmath>
#include <thread>

#include "base/user_error.h"
#include "config/case_config_toml_internal.h"
#include "occlude/planner/evaluation.h"

namespace occlude::app {
namespace {

[[noreturn]] void Fail(const CaseConfig& config, const std::string& key, const std::string& what) {
  throw UserError(config.file.string() + ": " + key + ": " + what);
}

double NumberOption(const CaseConfig& config, const std::string& key,
                    const SolverSettings::Value& v) {
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  Fail(config, "solver.options." + key, "must be a number");
}

std::int64_t IntegerOption(const CaseConfig& config, const std::string& key,
                           const SolverSettings::Value& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return *i;
  Fail(config, "solver.options." + key, "must be an integer");
}

std::string StringOption(const CaseConfig& config, const std::string& key,
                         const SolverSettings::Value& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  Fail(config, "solver.options." + key, "must be a string");
}

// The option `word` most likely meant (config/case_config_toml_internal.h), empty when even
// that one is more than about half of `word` away.
std::string Closest(const std::string& word, const std::vector<std::string>& keys) {
  std::string best = toml_config::ClosestKey(word, keys);
  return EditDistance(word, best) < word.size() / 2 + 2 ? best : std::string();
}

void ApplyOption(const CaseConfig& config, const std::string& key, const SolverSettings::Value& v,
                 planner::PlanRequest* r) {
  const std::string path = "solver.options." + key;
  try {
    if (key == "nlopt_local") {
      r->nlopt_local = planner::NloptLocalMethodFromName(StringOption(config, key, v));
    } else if (key == "global_samples") {
      r->num_global_samples = static_cast<int>(IntegerOption(config, key, v));
    } else if (key == "max_evaluations") {
      r->max_evaluations = static_cast<int>(IntegerOption(config, key, v));
    } else if (key == "penetration_measure") {
      const std::string m = StringOption(config, key, v);
      if (m == "max")
        r->penetration_measure = planner::PenetrationMeasure::kMax;
      else if (m == "outlier-area")
        r->penetration_measure = planner::PenetrationMeasure::kOutlierArea;
      else if (m == "percentile")
        r->penetration_measure = planner::PenetrationMeasure::kPercentile;
      else
        Fail(config, path,
             "'" + m + "' is not a measure; use \"outlier-area\", \"max\" or \"percentile\"");
    } else if (key == "outlier_area_mm2") {
      r->outlier_area_mm2 = NumberOption(config, key, v);
    } else if (key == "penetration_percentile") {
      r->penetration_percentile = NumberOption(config, key, v);
    } else if (key == "spike_patch_max_mm2") {
      r->spike_patch_max_mm2 = NumberOption(config, key, v);
    } else if (key == "bilateral_posterior_weight") {
      r->bilateral_posterior_weight = NumberOption(config, key, v);
    } else if (key == "seat_window_mm") {
      r->seat_window_mm = NumberOption(config, key, v);
    } else if (key == "seat_scale_mm") {
      r->seat_scale_mm = NumberOption(config, key, v);
    } else if (key == "seat_penetration_allowance_mm") {
      r->seat_penetration_allowance_mm = NumberOption(config, key, v);
    } else if (key == "seat_min_facing") {
      r->seat_min_facing = NumberOption(config, key, v);
    } else if (key == "distinct_translation_mm") {
      r->distinct_translation_mm = NumberOption(config, key, v);
    } else if (key == "distinct_rotation_deg") {
      r->distinct_rotation_deg = NumberOption(config, key, v);
    } else {
      const std::string near = Closest(key, SolverOptionKeys());
      Fail(config, path,
           "unknown solver option" +
               (near.empty() ? std::string("") : "; did you mean '" + near + "'?") +
               " (see plan_config.h or the README)");
    }
  } catch (const std::invalid_argument& e) {
    Fail(config, path, e.what());
  }
}

}  // namespace

const std::vector<std::string>& SolverOptionKeys() {
  static const std::vector<std::string> keys = {"nlopt_local",
                                                "global_samples",
                                                "max_evaluations",
                                                "penetration_measure",
                                                "outlier_area_mm2",
                                                "penetration_percentile",
                                                "spike_patch_max_mm2",
                                                "bilateral_posterior_weight",
                                                "seat_window_mm",
                                                "seat_scale_mm",
                                                "seat_penetration_allowance_mm",
                                                "seat_min_facing",
                                                "distinct_translation_mm",
                                                "distinct_rotation_deg"};
  return keys;
}

planner::PlanRequest PlanRequestFromConfig(const CaseConfig& config,
                                           const Eigen::Isometry3d& X_LU_start,
                                           const Eigen::Vector3d& pivot_L) {
  planner::PlanRequest r;
  r.X_LU_start = X_LU_start;
  r.pivot_L = X_LU_start * pivot_L;
  if (config.solver.name != "auto") {
    try {
      r.solver = planner::SolverKindFromName(config.solver.name);
    } catch (const std::invalid_argument& e) {
      Fail(config, "solver.name", std::string(e.what()) + " (or \"auto\")");
    }
  }
  r.num_starts = config.solver.starts;
  r.seed = static_cast<std::uint32_t>(config.solver.seed);
  r.num_threads = config.solver.threads > 0
                      ? config.solver.threads
                      : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  r.max_proposals = config.solver.proposals;
  r.max_seconds = config.solver.max_seconds;
  r.contact_band_mm = config.contact_band_mm;
  r.max_penetration_mm = config.max_penetration_mm;
  for (int i = 0; i < 3; ++i) {
    r.lower_bound.translation_mm[i] = config.bounds[static_cast<std::size_t>(i)].min;
    r.upper_bound.translation_mm[i] = config.bounds[static_cast<std::size_t>(i)].max;
    r.lower_bound.rotation_deg[i] = config.bounds[static_cast<std::size_t>(i + 3)].min;
    r.upper_bound.rotation_deg[i] = config.bounds[static_cast<std::size_t>(i + 3)].max;
  }
  for (int i = 0; i < kNumDofs; ++i)
    r.locked[static_cast<std::size_t>(i)] = config.locked[static_cast<std::size_t>(i)];
  for (const auto& [key, value] : config.solver.options) ApplyOption(config, key, value, &r);
  try {
    planner::ValidateRequest(r);
  } catch (const std::invalid_argument& e) {
    throw UserError(config.file.string() +
                    ": the search settings ([solver], [bounds], [contact]): " + e.what());
  }
  return r;
}

std::array<bool, kNumDofs> RefineHeldDofs(const CaseConfig& config) {
  std::array<bool, kNumDofs> held = config.refine.hold;
  if (config.refine.hold_adjusted) {
    for (int i = 0; i < 3; ++i) {
      held[static_cast<std::size_t>(i)] = config.adjust.translation_mm[i] != 0.0;
      held[static_cast<std::size_t>(i + 3)] = config.adjust.rotation_deg[i] != 0.0;
    }
  }
  for (int i = 0; i < kNumDofs; ++i) {
    if (config.locked[static_cast<std::size_t>(i)]) held[static_cast<std::size_t>(i)] = false;
  }
  return held;
}

}  // namespace occlude::app
