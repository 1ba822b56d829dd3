// The outputs of `occlude validate`: validate.csv (one row per run), validate-summary.csv and
// .txt (per solver and magnitude), and the charts (see validate.h).
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

#include "base/text_format.h"
#include "chart/chart.h"
#include "validate/validate.h"

namespace occlude::app {
namespace {

std::string MagnitudeLabel(const Magnitude& m) {
  std::ostringstream s;
  s << m.mm << " mm / " << m.deg << " deg";
  return s.str();
}

}  // namespace

std::string ValidateCsv(const ValidateResult& result) {
  std::ostringstream s;
  s << "solver,magnitude_mm,magnitude_deg,start,err_mm,err_deg,max_penetration_mm,contact_area_mm2,"
       "seconds,"
       "success,start_err_mm,start_err_deg,constrained_penetration_mm,outliers,contact_samples,"
       "consensus_mm,"
       "tx_mm,ty_mm,tz_mm,rx_deg,ry_deg,rz_deg,status,evaluations\n";
  s << std::setprecision(6);
  for (const ValidateRun& r : result.runs) {
    s << planner::ToString(r.solver) << ',' << r.magnitude.mm << ',' << r.magnitude.deg << ','
      << r.start << ',' << r.error.translation_mm << ',' << r.error.rotation_deg << ','
      << r.max_penetration_mm << ',' << r.contact_area_mm2 << ',' << r.seconds << ','
      << (r.success ? 1 : 0) << ',' << r.start_error.translation_mm << ','
      << r.start_error.rotation_deg << ',' << r.constrained_penetration_mm << ',' << r.outliers
      << ',' << r.contact_samples << ',' << r.consensus_mm << ',' << r.found.translation_mm.x()
      << ',' << r.found.translation_mm.y() << ',' << r.found.translation_mm.z() << ','
      << r.found.rotation_deg.x() << ',' << r.found.rotation_deg.y() << ','
      << r.found.rotation_deg.z() << ',' << r.status << ',' << r.evaluations << '\n';
  }
  return s.str();
}

std::string ValidateSummaryCsv(const ValidateResult& result) {
  std::ostringstream s;
  s << "solver,magnitude_mm,magnitude_deg,runs,success_rate,median_err_mm,p95_err_mm,median_err_"
       "deg,p95_err_deg,"
       "median_seconds,worst_penetration_mm,worst_max_penetration_mm,consensus_err_mm,consensus_"
       "err_deg,"
       "median_consensus_mm,within_consensus,consensus_contact_mm2\n";
  s << std::setprecision(6);
  for (const ValidateSummary& r : result.summary) {
    s << planner::ToString(r.solver) << ',' << r.magnitude.mm << ',' << r.magnitude.deg << ','
      << r.runs << ',' << r.success_rate << ',' << r.median_err_mm << ',' << r.p95_err_mm << ','
      << r.median_err_deg << ',' << r.p95_err_deg << ',' << r.median_seconds << ','
      << r.worst_penetration_mm << ',' << r.worst_max_penetration_mm << ','
      << r.medoid_error.translation_mm << ',' << r.medoid_error.rotation_deg << ','
      << r.median_consensus_mm << ',' << r.within_consensus << ',' << r.medoid_contact_mm2 << '\n';
  }
  return s.str();
}

std::string ReferencePathCsv(const ValidateResult& result) {
  std::ostringstream s;
  s << "s,from_reference_mm,from_reference_deg,contact_area_mm2,contact_samples,max_penetration_mm,"
       "constrained_penetration_mm,deep_samples,posterior_share,dominates_reference\n";
  s << std::setprecision(6);
  const auto& path = result.reference_check.path;
  for (const planner::PathPoint& p : path) {
    const planner::PoseEvaluation& e = p.evaluation;
    s << p.s << ',' << p.from_start.translation_mm << ',' << p.from_start.rotation_deg << ','
      << e.contact_area_mm2 << ',' << e.contact_samples << ',' << e.max_penetration_mm << ','
      << e.constrained_penetration_mm << ',' << e.deep_samples << ',' << e.posterior_share << ','
      << (planner::Dominates(e, path.front().evaluation) ? 1 : 0) << '\n';
  }
  return s.str();
}

namespace {

void ReferenceCheckText(const ValidateResult& result, const ValidateOptions& options,
                        std::ostream& s) {
  const ReferenceCheck& c = result.reference_check;
  if (c.path.empty()) return;
  const planner::PoseEvaluation& ref = c.path.front().evaluation;
  const planner::PoseEvaluation& consensus = c.path.back().evaluation;
  s << "\nreference check (last stage; reference-path.csv): the consensus of all "
    << result.runs.size() << " runs\nlies " << Fixed(c.consensus_error.translation_mm, 3)
    << " mm / " << Fixed(c.consensus_error.rotation_deg, 2) << " deg from the reference, with "
    << Fixed(consensus.contact_area_mm2, 2) << " mm^2 of contact and "
    << Fixed(consensus.constrained_penetration_mm, 3)
    << " mm of outlier-robust\npenetration (reference: " << Fixed(ref.contact_area_mm2, 2)
    << " mm^2, " << Fixed(ref.constrained_penetration_mm, 3) << " mm).\n";
  auto describe = [&](int k) {
    const planner::PathPoint& p = c.path[static_cast<std::size_t>(k)];
    return Fixed(p.from_start.translation_mm, 3) + " mm / " + Fixed(p.from_start.rotation_deg, 2) +
           " deg from it, " + Fixed(p.evaluation.contact_area_mm2, 2) + " mm^2 of contact, " +
           Fixed(p.evaluation.constrained_penetration_mm, 3) + " mm of penetration";
  };
  const std::string bar =
      Fixed(options.success_mm, 2) + " mm / " + Fixed(options.success_deg, 1) + " deg";
  if (c.nearest_dominating < 0) {
    s << "No pose on the straight path from the reference to the consensus dominates the reference "
         "(more contact\n"
         "and no deeper penetration); that is no proof that the reference is the optimum.\n";
  } else if (c.nearest_dominating_beyond_bar < 0) {
    s << "Poses on the path dominate the reference (more contact, no deeper penetration) only "
         "within the success\n"
         "bar ("
      << bar << "), where a solver that reaches them still succeeds. Most contact at\n"
      << describe(c.most_contact_dominating) << ".\n";
  } else {
    s << "The reference is DOMINATED (more contact, no deeper penetration) beyond the success bar ("
      << bar << "):\nat " << describe(c.nearest_dominating_beyond_bar) << ";\nmost contact at "
      << describe(c.most_contact_dominating) << ".\n"
      << "Every objective that rewards contact and penalizes penetration prefers that pose, beyond "
         "the bar, to\n"
         "the reference: errors against the reference measure how far it is from such a seat, not "
         "how well the\n"
         "solvers converge (see 'consensus', 'spread' and 'within').\n";
  }
}

}  // namespace

std::string ValidateSummaryText(const ValidateResult& result, const ValidateOptions& options,
                                const std::string& machine) {
  std::ostringstream s;
  s << "occlude validate: case " << result.case_name << "\n";
  s << "machine: " << machine << "; each run single-threaded, thread CPU time\n";
  s << "schedule: voxels";
  for (const double v : options.voxels_mm) s << ' ' << v;
  s << " mm" << (options.exact_last ? " + exact" : "") << "; " << options.starts
    << " starts per magnitude, seed " << options.seed << "; band " << options.contact_band_mm
    << " mm, max penetration " << options.max_penetration_mm << " mm; success within "
    << options.success_mm << " mm and " << options.success_deg << " deg\n";
  s << "oracles built in " << Fixed(result.build_seconds, 1) << " s\n";
  const planner::PoseEvaluation& ref = result.reference;
  s << "reference pose as given: contact " << Fixed(ref.contact_area_mm2, 2)
    << " mm^2, max penetration " << Fixed(ref.max_penetration_mm, 3) << " mm (outlier-robust "
    << Fixed(ref.constrained_penetration_mm, 3) << " mm, " << ref.outliers.size()
    << " outlier samples)\n\n";
  s << std::left << std::setw(15) << "solver" << std::setw(17) << "magnitude" << std::right
    << std::setw(5) << "runs" << std::setw(9) << "success" << std::setw(10) << "med mm"
    << std::setw(9) << "p95 mm" << std::setw(9) << "med deg" << std::setw(9) << "p95 deg"
    << std::setw(8) << "med s" << std::setw(9) << "pen max" << std::setw(12) << "consensus"
    << std::setw(9) << "spread" << std::setw(8) << "within"
    << "\n";
  for (const ValidateSummary& r : result.summary) {
    const bool closing = r.magnitude.mm == 0.0 && r.magnitude.deg == 0.0;
    s << std::left << std::setw(15) << planner::ToString(r.solver) << std::setw(17)
      << (closing ? std::string("closing") : MagnitudeLabel(r.magnitude)) << std::right
      << std::setw(5) << r.runs << std::setw(8) << Fixed(100.0 * r.success_rate, 0) << "%"
      << std::setw(10) << Fixed(r.median_err_mm, 3) << std::setw(9) << Fixed(r.p95_err_mm, 3)
      << std::setw(9) << Fixed(r.median_err_deg, 2) << std::setw(9) << Fixed(r.p95_err_deg, 2)
      << std::setw(8) << Fixed(r.median_seconds, 2) << std::setw(9)
      << Fixed(r.worst_penetration_mm, 3) << std::setw(12)
      << (" " + Fixed(r.medoid_error.translation_mm, 2) + "/" +
          Fixed(r.medoid_error.rotation_deg, 2))
      << std::setw(9) << Fixed(r.median_consensus_mm, 3) << std::setw(7)
      << Fixed(100.0 * r.within_consensus, 0) << "%\n";
  }
  s << "\nerrors against the reference pose: the largest displacement of the pivot and the incisor "
       "and molar\n"
       "reference points (mm) and the relative rotation (deg); 'pen max' = largest outlier-robust "
       "penetration of\n"
       "the found poses; 'consensus' = error of the medoid of the found poses (mm/deg); 'spread' = "
       "median\n"
       "displacement of the runs from it; 'within' = share of runs within the success bar of the "
       "consensus.\n"
       "'closing' rows start at the reference itself: their errors are how far the search moved.\n";
  ReferenceCheckText(result, options, s);
  return s.str();
}

namespace {

// Stability (success rate, and the share within the bar of the consensus, dashed) and error
// (median, and the 95th percentile dashed) against the magnitude, one colour per solver.
std::pair<LineChart, LineChart> MagnitudeCharts(const ValidateResult& result,
                                                const ValidateOptions& options,
                                                const std::string& subtitle) {
  std::vector<std::string> labels;
  for (const Magnitude& m : options.magnitudes) labels.push_back(MagnitudeLabel(m));
  auto index_of = [&](const Magnitude& m) {
    for (std::size_t i = 0; i < options.magnitudes.size(); ++i) {
      if (options.magnitudes[i].mm == m.mm && options.magnitudes[i].deg == m.deg)
        return static_cast<double>(i);
    }
    return -1.0;
  };
  LineChart stability;
  stability.title = "Stability: success rate against start perturbation (" + result.case_name + ")";
  stability.x_label = "perturbation of the start (translation / rotation, at most)";
  stability.y_label = "success rate, % of runs";
  stability.subtitle = subtitle + " | success: within " + Fixed(options.success_mm, 1) +
                       " mm and " + Fixed(options.success_deg, 0) +
                       " deg of the reference; dashed: of the runs' consensus";
  stability.x_categories = labels;
  stability.y_include = {0.0, 100.0};
  LineChart error = stability;
  error.y_include.clear();
  error.title = "Pose error against start perturbation (" + result.case_name + ")";
  error.y_label = "translation error, mm (log)";
  error.subtitle = subtitle + " | solid: median, dashed: 95th percentile";
  error.log_y = true;
  error.references = {{options.success_mm, "success bar"}};
  int color = 0;
  for (const planner::SolverKind s : options.solvers) {
    ChartSeries ok{planner::ToString(s), {}, {}, color, false};
    ChartSeries consensus{std::string(planner::ToString(s)) + ", consensus", {}, {}, color, true};
    ChartSeries med{std::string(planner::ToString(s)) + " median", {}, {}, color, false};
    ChartSeries p95{std::string(planner::ToString(s)) + " p95", {}, {}, color, true};
    for (const ValidateSummary& r : result.summary) {
      if (r.solver != s) continue;
      const double x = index_of(r.magnitude);
      ok.x.push_back(x);
      ok.y.push_back(100.0 * r.success_rate);
      consensus.x.push_back(x);
      consensus.y.push_back(100.0 * r.within_consensus);
      med.x.push_back(x);
      med.y.push_back(std::max(1e-3, r.median_err_mm));
      p95.x.push_back(x);
      p95.y.push_back(std::max(1e-3, r.p95_err_mm));
    }
    stability.series.push_back(ok);
    stability.series.push_back(consensus);
    error.series.push_back(med);
    error.series.push_back(p95);
    ++color;
  }
  return {stability, error};
}

// Thread CPU time against the pose error of every run, one colour per solver.
LineChart TimeErrorChart(const ValidateResult& result, const ValidateOptions& options,
                         const std::string& subtitle) {
  LineChart scatter;
  scatter.title = "Time against pose error, every run (" + result.case_name + ")";
  scatter.subtitle = subtitle;
  scatter.x_label = "thread CPU time per run, s (log)";
  scatter.y_label = "translation error against the reference, mm (log)";
  scatter.log_x = scatter.log_y = true;
  scatter.references = {{options.success_mm, "success bar"}};
  int color = 0;
  for (const planner::SolverKind s : options.solvers) {
    ChartSeries pts{planner::ToString(s), {}, {}, color++, false};
    pts.markers_only = true;
    for (const ValidateRun& r : result.runs) {
      if (r.solver != s) continue;
      pts.x.push_back(std::max(1e-3, r.seconds));
      pts.y.push_back(std::max(1e-3, r.error.translation_mm));
    }
    scatter.series.push_back(pts);
  }
  return scatter;
}

// The reference check: contact along the path from the reference to the consensus, each pose
// labelled with its outlier-robust penetration; the poses dominating the reference marked.
LineChart ReferencePathChart(const ValidateResult& result, const ValidateOptions& options,
                             const std::string& subtitle) {
  const ReferenceCheck& check = result.reference_check;
  LineChart path;
  path.title =
      "Reference check: from the reference to the consensus of the runs (" + result.case_name + ")";
  path.subtitle = subtitle + " | labels: outlier-robust penetration, um (limit " +
                  Fixed(1000.0 * options.max_penetration_mm, 0) +
                  "); dominates: more contact, no deeper penetration than the reference";
  path.x_label = "displacement from the reference pose, mm (largest of the reference points)";
  path.y_label = "contact area within the band, mm^2";
  path.y_include = {0.0};
  ChartSeries contact{"contact along the path", {}, {}, 0, false};
  ChartSeries dominating{"dominates the reference", {}, {}, 1, false};
  dominating.markers_only = true;
  for (const planner::PathPoint& p : check.path) {
    contact.x.push_back(p.from_start.translation_mm);
    contact.y.push_back(p.evaluation.contact_area_mm2);
    contact.labels.push_back(Fixed(1000.0 * p.evaluation.constrained_penetration_mm, 0));
    if (planner::Dominates(p.evaluation, check.path.front().evaluation)) {
      dominating.x.push_back(p.from_start.translation_mm);
      dominating.y.push_back(p.evaluation.contact_area_mm2);
    }
  }
  path.series.push_back(contact);
  if (!dominating.x.empty()) path.series.push_back(dominating);
  return path;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> ValidateCharts(const ValidateResult& result,
                                                                const ValidateOptions& options,
                                                                const std::string& subtitle) {
  std::vector<std::pair<std::string, std::string>> out;
  const auto [stability, error] = MagnitudeCharts(result, options, subtitle);
  out.emplace_back("stability.png", RenderLineChartPng(stability));
  out.emplace_back("error.png", RenderLineChartPng(error));
  out.emplace_back("time-vs-error.png",
                   RenderLineChartPng(TimeErrorChart(result, options, subtitle)));
  if (!result.reference_check.path.empty()) {
    out.emplace_back("reference-path.png",
                     RenderLineChartPng(ReferencePathChart(result, options, subtitle)));
  }
  return out;
}

}  // namespace occlude::app
