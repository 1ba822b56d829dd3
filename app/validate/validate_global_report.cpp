// The outputs of `occlude validate --global`: validate.csv (one row per run, with start_kind
// and the seat columns), validate-summary.csv and .txt (per start kind and solver) and
// stability.png (see validate_global.h).
#include <algorithm>
#include <iomanip>
#include <sstream>

#include "base/text_format.h"
#include "chart/chart.h"
#include "session/clinical_judge.h"
#include "validate/validate_global.h"

namespace occlude::app {

std::string GlobalValidateCsv(const GlobalValidateResult& result) {
  std::ostringstream s;
  s << "start_kind,solver,start,magnitude_mm,magnitude_deg,success,err_mm,err_deg,seat_success,"
       "seat_err_mm,seat_err_deg,seat_rank,proposals,excluded,start_err_mm,start_err_deg,"
       "contact_area_mm2,constrained_penetration_mm,max_penetration_mm,seconds,wall_seconds,"
       "status,evaluations,top_molar_class,top_canine_class,targets_met,top_penalty\n";
  s << std::setprecision(6);
  for (const GlobalValidateRun& g : result.runs) {
    const ValidateRun& r = g.run;
    s << g.start_kind << ',' << planner::ToString(r.solver) << ',' << r.start << ','
      << r.magnitude.mm << ',' << r.magnitude.deg << ',' << (r.success ? 1 : 0) << ','
      << r.error.translation_mm << ',' << r.error.rotation_deg << ',' << (g.seat_success ? 1 : 0)
      << ',' << g.seat_err_mm << ',' << g.seat_err_deg << ',' << g.seat_rank << ',' << g.proposals
      << ',' << g.excluded << ',' << r.start_error.translation_mm << ','
      << r.start_error.rotation_deg << ',' << r.contact_area_mm2 << ','
      << r.constrained_penetration_mm << ',' << r.max_penetration_mm << ',' << r.seconds << ','
      << g.wall_seconds << ',' << r.status << ',' << r.evaluations << ',' << g.top_molar_class
      << ',' << g.top_canine_class << ',' << (g.targets_met ? 1 : 0) << ',' << g.top_penalty
      << '\n';
  }
  return s.str();
}

std::string GlobalValidateSummaryCsv(const GlobalValidateResult& result) {
  std::ostringstream s;
  s << "start_kind,solver,runs,success_rate,seat_success_rate,seat_among_rate,median_seat_err_mm,"
       "p95_seat_err_mm,median_seat_err_deg,median_err_mm,median_seconds,max_seconds,"
       "median_wall_seconds,worst_penetration_mm,targets_met_rate\n";
  s << std::setprecision(6);
  for (const GlobalValidateSummary& r : result.summary) {
    s << r.start_kind << ',' << planner::ToString(r.solver) << ',' << r.runs << ','
      << r.success_rate << ',' << r.seat_success_rate << ',' << r.seat_among_rate << ','
      << r.median_seat_err_mm << ',' << r.p95_seat_err_mm << ',' << r.median_seat_err_deg << ','
      << r.median_err_mm << ',' << r.median_seconds << ',' << r.max_seconds << ','
      << r.median_wall_seconds << ',' << r.worst_penetration_mm << ',' << r.targets_met_rate
      << '\n';
  }
  return s.str();
}

std::string GlobalValidateSummaryText(const GlobalValidateResult& result,
                                      const ValidateOptions& options, const std::string& machine) {
  std::ostringstream s;
  s << "occlude validate --global: case " << result.case_name << "\n";
  s << "machine: " << machine << "; each run single-threaded, thread CPU time of the search\n";
  s << "schedule: voxels";
  for (const double v : options.voxels_mm) s << ' ' << v;
  s << " mm" << (options.exact_last ? " + exact" : "") << "; " << options.starts
    << " starts per kind, seed " << options.seed << "; success within " << options.success_mm
    << " mm and " << options.success_deg << " deg\n";
  s << "clinical targets" << (options.clinical.from_config ? " (--clinical)" : " (the default)")
    << ": " << TargetsLine(options.clinical);
  if (std::find(options.global_kinds.begin(), options.global_kinds.end(), "cusp") !=
      options.global_kinds.end())
    s << "; cusp starts " << Fixed(options.cusp_period_mm, 1) << " mm off";
  s << "\n";
  s << "arch analysis and the reference's oracles in " << Fixed(result.build_seconds, 1)
    << " s (wall)\n";
  s << "seat of the reference (the best seat of its closing run): "
    << Fixed(result.seat_from_reference.translation_mm, 3) << " mm / "
    << Fixed(result.seat_from_reference.rotation_deg, 2) << " deg from the reference, contact "
    << Fixed(result.seat.evaluation.contact_area_mm2, 2) << " mm^2\n\n";
  s << std::left << std::setw(10) << "kind" << std::setw(15) << "solver" << std::right
    << std::setw(5) << "runs" << std::setw(7) << "seat" << std::setw(8) << "among" << std::setw(9)
    << "vs ref" << std::setw(11) << "seat mm" << std::setw(9) << "p95 mm" << std::setw(9)
    << "seat deg" << std::setw(8) << "cpu s" << std::setw(8) << "max s" << std::setw(8) << "wall s"
    << std::setw(9) << "pen max" << std::setw(9) << "targets"
    << "\n";
  for (const GlobalValidateSummary& r : result.summary) {
    s << std::left << std::setw(10) << r.start_kind << std::setw(15) << planner::ToString(r.solver)
      << std::right << std::setw(5) << r.runs << std::setw(6)
      << Fixed(100.0 * r.seat_success_rate, 0) << "%" << std::setw(7)
      << Fixed(100.0 * r.seat_among_rate, 0) << "%" << std::setw(8)
      << Fixed(100.0 * r.success_rate, 0) << "%" << std::setw(11) << Fixed(r.median_seat_err_mm, 3)
      << std::setw(9) << Fixed(r.p95_seat_err_mm, 3) << std::setw(9)
      << Fixed(r.median_seat_err_deg, 2) << std::setw(8) << Fixed(r.median_seconds, 2)
      << std::setw(8) << Fixed(r.max_seconds, 2) << std::setw(8) << Fixed(r.median_wall_seconds, 2)
      << std::setw(9) << Fixed(r.worst_penetration_mm, 3) << std::setw(8)
      << Fixed(100.0 * r.targets_met_rate, 0) << "%\n";
  }
  s << "\n'seat' = seat_success: the top proposal within the bar of the seat of the reference; "
       "'among' = the seat\namong the "
       "proposals; 'vs ref' = the top proposal within the bar of the reference itself; errors "
       "(median, 95th\npercentile) of the top proposal against the seat; 'targets' = the top "
       "proposal meets\nevery measured clinical target (validate.csv: its molar and canine "
       "classes, right/left).\n";
  return s.str();
}

std::vector<std::pair<std::string, std::string>> GlobalValidateCharts(
    const GlobalValidateResult& result, const ValidateOptions& options,
    const std::string& subtitle) {
  LineChart chart;
  chart.title = "Global search: seat found per start kind (" + result.case_name + ")";
  chart.x_label = "start kind";
  chart.y_label = "success rate, % of runs";
  chart.subtitle = subtitle + " | solid: top proposal at the seat of the reference (within " +
                   Fixed(options.success_mm, 1) + " mm and " + Fixed(options.success_deg, 0) +
                   " deg); dashed: at the reference";
  for (const GlobalValidateSummary& r : result.summary) {
    if (std::find(chart.x_categories.begin(), chart.x_categories.end(), r.start_kind) ==
        chart.x_categories.end())
      chart.x_categories.push_back(r.start_kind);
  }
  chart.y_include = {0.0, 100.0};
  int color = 0;
  for (const planner::SolverKind solver : options.solvers) {
    ChartSeries seat{planner::ToString(solver), {}, {}, color, false};
    ChartSeries ref{std::string(planner::ToString(solver)) + ", reference", {}, {}, color, true};
    for (const GlobalValidateSummary& r : result.summary) {
      if (r.solver != solver) continue;
      const auto& kinds = chart.x_categories;
      const double x =
          static_cast<double>(std::find(kinds.begin(), kinds.end(), r.start_kind) - kinds.begin());
      seat.x.push_back(x);
      seat.y.push_back(100.0 * r.seat_success_rate);
      ref.x.push_back(x);
      ref.y.push_back(100.0 * r.success_rate);
    }
    chart.series.push_back(seat);
    chart.series.push_back(ref);
    ++color;
  }
  return {{"stability.png", RenderLineChartPng(chart)}};
}

}  // namespace occlude::app
