// `occlude validate --global`: the global search (planner/global_search.h) from starts of
// several kinds (column `start_kind`; ValidateOptions::global_kinds, by default the first
// three), scored against the reference and against the seat of the reference (the best seat
// the local search reaches from the reference itself: coarse-to-fine with its internal starts
// within the bound margins, as validate's closing run 0:0, each result polished as the global
// search polishes its seats, PlanRequest::polish):
//   near:     today's perturbations (validate.h), start k at magnitude k mod the magnitudes;
//   sagittal: the reference shifted along the arch by 3-12 mm either way plus up to 10 deg
//             (planner/global_starts.h);
//   apart:    the upper turned uniformly at random and moved 20-60 mm away;
//   cusp:     the reference shifted a cusp period (cusp_period_mm) along the arch, forward (the
//             Class II way) for even starts and back for odd ones, plus up to 0.5 mm / 3 deg.
// A start is the upper as a file would bring it: the upper mesh moved to the start pose and
// its oracles built again there; the arches are the case's arch analysis (session/
// case_analysis.h) of the jaws at the reference, the upper's carried by the start motion. Each
// solver of the options runs in global scope (GlobalRequest::local.solver), single-threaded,
// ranked by the clinical targets of the options (the default ranking unless --clinical). Per run:
// success against the reference as today; seat_success = the top proposal within the success bar of
// the seat, seat_err_mm / _deg its errors, seat_rank the rank of the first proposal within the bar
// (0: none); the top proposal's relationships (molar and canine class per side) and whether it
// meets every measured target (targets_met).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "validate/validate.h"

namespace occlude::app {

struct GlobalValidateRun {
  std::string start_kind;  ///< "near", "sagittal", "apart" or "cusp"
  ValidateRun run;         ///< solver, start, errors against the reference, the top proposal
  bool seat_success = false;
  double seat_err_mm = 0.0, seat_err_deg = 0.0;
  int seat_rank = 0;
  int proposals = 0, excluded = 0;
  double wall_seconds = 0.0;
  /// The top proposal's molar and canine class, right/left ("I/II"; "?" when not measured),
  /// whether it meets every measured target and its ranking penalty.
  std::string top_molar_class = "-", top_canine_class = "-";
  bool targets_met = false;
  double top_penalty = 0.0;
};

struct GlobalValidateSummary {
  std::string start_kind;
  planner::SolverKind solver = planner::SolverKind::kCoarseToFine;
  int runs = 0;
  double success_rate = 0.0;       ///< against the reference
  double seat_success_rate = 0.0;  ///< top proposal at the seat
  double seat_among_rate = 0.0;    ///< the seat among the proposals
  double targets_met_rate = 0.0;   ///< top proposal meets every measured target
  double median_seat_err_mm = 0.0, p95_seat_err_mm = 0.0, median_seat_err_deg = 0.0;
  double median_err_mm = 0.0;
  double median_seconds = 0.0, max_seconds = 0.0;  ///< thread CPU of the search
  double median_wall_seconds = 0.0;
  double worst_penetration_mm = 0.0;
};

struct GlobalValidateResult {
  std::string case_name;
  planner::Proposal seat;  ///< the seat of the reference
  planner::PoseError seat_from_reference;
  std::vector<GlobalValidateRun> runs;
  std::vector<GlobalValidateSummary> summary;  ///< per start kind, then solver
  double build_seconds = 0.0;
};

/// Every start kind, in output order: near, sagittal, apart, cusp.
const std::vector<std::string>& GlobalStartKinds();

/// options.starts starts per kind of options.global_kinds for every solver. Throws UserError
/// for a kind not in GlobalStartKinds(), when the arch analysis finds no teeth or the arches
/// cannot face each other.
GlobalValidateResult RunGlobalValidation(const JawPair& jaws, const ValidateOptions& options);

std::string GlobalValidateCsv(const GlobalValidateResult& result);
std::string GlobalValidateSummaryCsv(const GlobalValidateResult& result);
std::string GlobalValidateSummaryText(const GlobalValidateResult& result,
                                      const ValidateOptions& options, const std::string& machine);
/// stability.png: seat_success (solid) and success against the reference (dashed) per start
/// kind, one colour per solver.
std::vector<std::pair<std::string, std::string>> GlobalValidateCharts(
    const GlobalValidateResult& result, const ValidateOptions& options,
    const std::string& subtitle);

}  // namespace occlude::app
