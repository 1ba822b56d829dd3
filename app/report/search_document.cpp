// The search's proposals and outliers as JSON and HTML (see search_document.h).
#include "report/search_document.h"

#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/json_values.h"
#include "base/text_format.h"
#include "report/relationships_json_internal.h"

namespace occlude::app {
namespace {

using nlohmann::json;

int ToothOfPart(const io::TriangleMesh* mesh, std::int32_t part) {
  if (mesh == nullptr || part < 0 || static_cast<std::size_t>(part) >= mesh->parts.size()) return 0;
  return mesh->parts[static_cast<std::size_t>(part)].tooth_number;
}

}  // namespace

std::string SearchJson(const SearchSummary& s, bool with_timings) {
  const planner::PlanResult& r = *s.result;
  json proposals = json::array();
  int rank = 0;
  for (const planner::Proposal& p : r.proposals) {
    const planner::PoseParameters q =
        planner::DecomposePose(p.X_LU, s.pivot_L, Eigen::Isometry3d::Identity());
    json teeth = json::array();
    for (const auto& part : p.evaluation.parts) {
      if (part.contact_area_mm2 <= 0.0 && part.penetration_area_mm2 <= 0.0) continue;
      teeth.push_back({{"tooth", ToothOfPart(s.upper_U, part.part)},
                       {"part", part.part},
                       {"contact_area_mm2", part.contact_area_mm2},
                       {"contact_samples", part.contact_samples},
                       {"max_penetration_mm", part.max_penetration_mm}});
    }
    json outliers = json::array();
    for (const planner::OutlierPoint& o : p.evaluation.outliers) {
      outliers.push_back({{"p_L", Vec(o.p_L)},
                          {"depth_mm", o.depth_mm},
                          {"area_mm2", o.area_mm2},
                          {"tooth", ToothOfPart(s.upper_U, o.part)},
                          {"kind", o.spike ? "spike patch" : "area budget"}});
    }
    json entry = {{"rank", ++rank},
                  {"X_LU", Matrix(p.X_LU.matrix())},
                  {"translation_mm", Vec(q.translation_mm)},
                  {"rotation_deg", Vec(q.rotation_deg)},
                  {"contact_area_mm2", p.evaluation.contact_area_mm2},
                  {"contact_samples", p.evaluation.contact_samples},
                  {"max_penetration_mm", p.evaluation.max_penetration_mm},
                  {"constrained_penetration_mm", p.evaluation.constrained_penetration_mm},
                  {"feasible", p.evaluation.feasible},
                  {"left_share", p.evaluation.left_share},
                  {"right_share", p.evaluation.right_share},
                  {"anterior_share", p.evaluation.anterior_share},
                  {"posterior_share", p.evaluation.posterior_share},
                  {"score", p.score},
                  {"seat_cost", p.seat_cost},
                  {"status", planner::ToString(p.status)},
                  {"message", p.message},
                  {"start_index", p.start_index},
                  {"teeth", teeth},
                  {"outliers", outliers}};
    if (with_timings) entry["cpu_seconds"] = p.cpu_seconds;
    if (s.analysis)
      entry["relationships"] = RelationshipsJson(RelationshipsAt(*s.analysis, p.X_LU));
    proposals.push_back(entry);
  }
  json j = {
      {"command", s.command},
      {"start", s.start_source},
      {"solver", planner::ToString(r.solver)},
      {"pivot_L_mm", Vec(s.pivot_L)},
      {"convention",
       "translation_mm / rotation_deg: about pivot_L_mm, relative to the pose as given (X_LU = I)"},
      {"starts_run", r.starts_run},
      {"starts_skipped_by_max_seconds", r.starts_skipped},
      {"evaluations", r.total_evaluations},
      {"proposals", proposals}};
  if (with_timings) {
    j["cpu_seconds"] = r.cpu_seconds;
    j["wall_seconds"] = r.wall_seconds;
  }
  return j.dump(2) + "\n";
}

std::string SearchHtml(const SearchSummary& s) {
  const planner::PlanResult& r = *s.result;
  std::ostringstream h;
  h << "<h2>Search (" << s.command << ", " << planner::ToString(r.solver)
    << ")</h2>\n<p class=\"note\">Started from " << s.start_source << "; " << r.starts_run
    << " local solves" << (r.starts_skipped ? " (some skipped by max_seconds)" : "") << ", "
    << r.total_evaluations
    << " evaluations. Poses about the pivot, relative to the jaws as given.</p>\n";
  h << "<table><tr><th>#</th><th>translation (mm)</th><th>rotation (deg)</th><th>contact "
       "(mm&sup2;)</th>"
       "<th>max penetration (mm)</th><th>constrained (mm)</th><th>seat "
       "cost</th><th>status</th></tr>\n";
  int rank = 0;
  for (const planner::Proposal& p : r.proposals) {
    const planner::PoseParameters q =
        planner::DecomposePose(p.X_LU, s.pivot_L, Eigen::Isometry3d::Identity());
    h << "<tr><td>" << ++rank << "</td><td>" << Fixed(q.translation_mm.x(), 3) << ", "
      << Fixed(q.translation_mm.y(), 3) << ", " << Fixed(q.translation_mm.z(), 3) << "</td><td>"
      << Fixed(q.rotation_deg.x(), 2) << ", " << Fixed(q.rotation_deg.y(), 2) << ", "
      << Fixed(q.rotation_deg.z(), 2) << "</td><td>" << Fixed(p.evaluation.contact_area_mm2, 2)
      << "</td><td>" << Fixed(p.evaluation.max_penetration_mm, 3) << "</td><td>"
      << Fixed(p.evaluation.constrained_penetration_mm, 3) << "</td><td>" << Fixed(p.seat_cost, 3)
      << "</td><td>" << planner::ToString(p.status) << "</td></tr>\n";
  }
  h << "</table>\n";
  if (!r.proposals.empty()) {
    const auto& outliers = r.proposals.front().evaluation.outliers;
    h << "<h3>Points treated as scan artefacts (best proposal)</h3>\n";
    if (outliers.empty()) {
      h << "<p class=\"note\">None: the penetration limit holds for every sample.</p>\n";
    } else {
      h << "<p class=\"note\">" << outliers.size()
        << " penetrating samples were left out of the penetration limit (spike patches: steeper "
           "than a hemisphere; "
           "area budget: the deepest samples up to the outlier area). The true maximum is still "
           "reported above.</p>\n"
           "<table><tr><th>position in L (mm)</th><th>depth (mm)</th><th>area "
           "(mm&sup2;)</th><th>tooth</th><th>kind</th></tr>\n";
      for (std::size_t i = 0; i < outliers.size() && i < 40; ++i) {
        const auto& o = outliers[i];
        h << "<tr><td>" << Fixed(o.p_L.x(), 2) << ", " << Fixed(o.p_L.y(), 2) << ", "
          << Fixed(o.p_L.z(), 2) << "</td><td>" << Fixed(o.depth_mm, 3) << "</td><td>"
          << Fixed(o.area_mm2, 3) << "</td><td>" << ToothOfPart(s.upper_U, o.part) << "</td><td>"
          << (o.spike ? "spike patch" : "area budget") << "</td></tr>\n";
      }
      h << "</table>\n";
      if (outliers.size() > 40)
        h << "<p class=\"note\">(" << outliers.size() - 40 << " more in metrics.json)</p>\n";
    }
  }
  return h.str();
}

}  // namespace occlude::app
