// metrics.json, pose.json and report.html (see report_document.h).
#include "report/report_document.h"

#include <cmath>
#include <ctime>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/json_values.h"
#include "base/output_files.h"
#include "report/relationships_json_internal.h"
#include "report/relationships_table.h"
#include "viewer/html_text.h"

namespace occlude::app {
namespace {

using nlohmann::json;

// How the voxel size and level were chosen (resolution_choice.h).
json ResolutionJson(const ResolutionChoice& r) {
  json j = {{"voxel_mm", r.chosen.voxel_mm},
            {"level", collision::ToString(r.chosen.level)},
            {"from", r.explicit_voxel ? "accuracy.voxel_mm" : "accuracy.accuracy_mm"},
            {"table", r.source},
            {"met", r.met},
            {"description", r.Describe()}};
  if (!r.explicit_voxel) j["accuracy_mm"] = r.accuracy_mm;
  if (r.measured) {
    j["measured_p95_err_mm"] = r.chosen.p95_err_mm;
    j["measured_max_err_mm"] = r.chosen.max_err_mm;
    j["measured_median_us"] = r.chosen.median_us;
  }
  return j;
}

json Settings(const CaseConfig& c, const ReportAnalysis& a) {
  json solver_options = json::object();
  for (const auto& [k, v] : c.solver.options) {
    std::visit([&, key = k](const auto& x) { solver_options[key] = x; }, v);
  }
  json bounds = json::object();
  json locked = json::array();
  for (int d = 0; d < kNumDofs; ++d) {
    const auto& b = c.bounds[static_cast<std::size_t>(d)];
    bounds[std::string(DofName(d)) + (d < 3 ? "_mm" : "_deg")] = json::array({b.min, b.max});
    if (c.locked[static_cast<std::size_t>(d)]) locked.push_back(DofName(d));
  }
  json oracles = json::array();  // the session's oracles: how much of the jaws each models
  for (const OracleModel& m : a.models) {
    json o = {{"voxel_mm", m.voxel_mm},
              {"bytes", m.bytes},
              {"build_s", m.build_seconds},
              {"region_of_interest", false}};
    if (m.region) {
      o["region_of_interest"] = {{"reach_mm", m.region->reach_mm},
                                 {"band_mm", m.region->band_mm},
                                 {"displacement_mm", m.region->displacement_mm},
                                 {"lower_kept", m.region->lower_kept},
                                 {"lower_total", m.region->lower_total},
                                 {"upper_kept", m.region->upper_kept},
                                 {"upper_total", m.region->upper_total},
                                 {"select_s", m.region->seconds},
                                 {"lower_cut", m.lower_cut},
                                 {"upper_cut", m.upper_cut}};
    }
    oracles.push_back(o);
  }
  return {{"units", std::string(io::LengthUnitName(c.units))},
          {"region_of_interest", c.region_of_interest},
          {"oracles", oracles},
          {"accuracy_mm", c.accuracy_mm},
          {"voxel_mm", a.voxel_mm},
          {"oracle_level", collision::ToString(a.oracle.level)},
          {"resolution", ResolutionJson(c.resolution)},
          {"sample_spacing_mm", c.sample_spacing_mm},
          {"contact_band_mm", c.contact_band_mm},
          {"max_penetration_mm", c.max_penetration_mm},
          {"map_max_mm", c.report.map_max_mm},
          {"map_penetration_from_mm", c.report.map_penetration_from_mm},
          {"map_reach_mm", a.reach_mm},
          {"solver",
           {{"name", c.solver.name},
            {"starts", c.solver.starts},
            {"seed", c.solver.seed},
            {"threads", c.solver.threads},
            {"proposals", c.solver.proposals},
            {"max_seconds", c.solver.max_seconds},
            {"options", solver_options}}},
          {"bounds", bounds},
          {"locked", locked}};
}

// `v` with `decimals` decimals for an HTML cell; a dash when not finite.
std::string HtmlNumber(double v, int decimals) {
  if (!std::isfinite(v)) return "&ndash;";
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(decimals);
  s << v;
  return s.str();
}

std::string Row(const std::string& name, const std::string& value) {
  return "<tr><th>" + name + "</th><td>" + value + "</td></tr>\n";
}

std::string Triple(const Eigen::Vector3d& v, int decimals) {
  return HtmlNumber(v.x(), decimals) + ", " + HtmlNumber(v.y(), decimals) + ", " +
         HtmlNumber(v.z(), decimals);
}

std::string PoseSection(const ReportInputs& in) {
  const ReportAnalysis& a = *in.analysis;
  std::ostringstream s;
  s << "<h2>Pose of the upper jaw</h2>\n<table>\n"
    << Row("source", HtmlEscape(in.pose_source))
    << Row("translation (mm)", Triple(a.params.translation_mm, 3))
    << Row("rotation (deg, rotation vector about the pivot)", Triple(a.params.rotation_deg, 3))
    << Row("pivot (mm, in L)", Triple(a.pivot_L, 2))
    << "</table>\n<p class=\"note\">X<sub>LU</sub> (mm):</p><pre>";
  const Eigen::Matrix4d m = a.X_LU.matrix();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) s << (c ? "  " : "") << HtmlNumber(m(r, c), c == 3 ? 4 : 7);
    s << "\n";
  }
  s << "</pre>\n";
  return s.str();
}

std::string MetricsSection(const ReportInputs& in) {
  const auto& o = in.analysis->oracle;
  const CaseConfig& c = *in.config;
  const bool ok = o.max_penetration_mm <= c.max_penetration_mm;
  std::ostringstream s;
  s << "<h2>Contact</h2>\n<table>\n"
    << Row("contact area (0-" + HtmlNumber(c.contact_band_mm, 2) + " mm)",
           HtmlNumber(o.contact_area_mm2, 2) + " mm&sup2;")
    << Row("contact spots", std::to_string(in.analysis->spots.size()))
    << Row("maximum penetration", HtmlNumber(o.max_penetration_mm, 3) + " mm " +
                                      (ok ? "<span class=\"ok\">(within the allowed "
                                          : "<span class=\"bad\">(EXCEEDS the allowed ") +
                                      HtmlNumber(c.max_penetration_mm, 3) + " mm)</span>")
    << Row("penetration area", HtmlNumber(o.penetration_area_mm2, 2) + " mm&sup2;")
    << Row("smallest gap", HtmlNumber(o.min_distance_mm, 3) + " mm")
    << Row("left / right share",
           HtmlNumber(100 * o.left_share, 0) + " % / " + HtmlNumber(100 * o.right_share, 0) + " %")
    << Row("anterior / posterior share", HtmlNumber(100 * o.anterior_share, 0) + " % / " +
                                             HtmlNumber(100 * o.posterior_share, 0) + " %")
    << "</table>\n";
  if (o.deep_samples > 0) {
    s << "<p class=\"bad\">" << o.deep_samples
      << " upper samples lie deeper inside the lower jaw than the measured range.</p>\n";
  }
  return s.str();
}

std::string TeethSection(const ReportInputs& in) {
  const auto& teeth = in.analysis->teeth;
  if (teeth.empty()) return "<h2>Per tooth</h2><p>The meshes carry no tooth numbers.</p>\n";
  std::ostringstream s;
  s << "<h2>Per tooth</h2>\n<table class=\"grid\"><tr><th>tooth</th><th>arch</th><th>contact area "
       "(mm&sup2;)</th>"
       "<th>contact spots</th><th>max penetration (mm)</th><th>penetration area "
       "(mm&sup2;)</th></tr>\n";
  for (const auto& t : teeth) {
    s << "<tr" << (t.contact_area_mm2 > 0 ? "" : " class=\"dim\"") << "><td>" << t.tooth
      << "</td><td>" << (t.upper ? "upper" : "lower") << "</td><td>"
      << HtmlNumber(t.contact_area_mm2, 2) << "</td><td>" << t.spots << "</td><td>"
      << HtmlNumber(t.max_penetration_mm, 3) << "</td><td>" << HtmlNumber(t.penetration_area_mm2, 2)
      << "</td></tr>\n";
  }
  s << "</table>\n";
  return s.str();
}

std::string SettingsSection(const ReportInputs& in) {
  const json settings = Settings(*in.config, *in.analysis);
  std::ostringstream s;
  s << "<h2>Settings</h2>\n<table>\n" << Row("config file", HtmlEscape(in.config->file.string()));
  for (const auto& [k, v] : settings.items()) s << Row(HtmlEscape(k), HtmlEscape(v.dump()));
  s << Row("meshes", std::to_string(in.jaws->lower_L->num_triangles()) + " lower, " +
                         std::to_string(in.jaws->upper_U->num_triangles()) + " upper triangles");
  for (const auto& [step, seconds] : in.analysis->timings_s)
    s << Row("time: " + HtmlEscape(step), HtmlNumber(seconds, 2) + " s");
  s << "</table>\n";
  return s.str();
}

constexpr const char* kStyle =
    "body{font-family:Helvetica,Arial,sans-serif;max-width:1100px;margin:24px auto;color:#222}"
    "h1{font-size:24px}h2{font-size:18px;margin-top:28px;border-bottom:1px solid #ccc}"
    "table{border-collapse:collapse;margin:8px 0}th,td{padding:3px "
    "10px;text-align:left;font-size:14px}"
    "table.grid td,table.grid th{border:1px solid #ddd;text-align:right}tr.dim{color:#999}"
    "img{max-width:100%;border:1px solid #ddd;margin:8px "
    "0}.ok{color:#070}.bad{color:#b00;font-weight:bold}"
    ".note{color:#555;font-size:13px}pre{font-size:13px}";

}  // namespace

std::string MetricsJson(const ReportInputs& in) {
  const ReportAnalysis& a = *in.analysis;
  const auto& o = a.oracle;
  json teeth = json::array();
  for (const auto& t : a.teeth) {
    teeth.push_back({{"tooth", t.tooth},
                     {"arch", t.upper ? "upper" : "lower"},
                     {"contact_area_mm2", t.contact_area_mm2},
                     {"contact_spots", t.spots},
                     {"max_penetration_mm", t.max_penetration_mm},
                     {"penetration_area_mm2", t.penetration_area_mm2}});
  }
  json spots = json::array();
  for (const auto& sp : a.spots) {
    spots.push_back({{"p_L", Vec(sp.p_L)},
                     {"area_mm2", sp.area_mm2},
                     {"samples", sp.samples},
                     {"upper_tooth", sp.upper_tooth},
                     {"lower_tooth", sp.lower_tooth}});
  }
  json timings = json::object();
  for (const auto& [step, seconds] : a.timings_s) timings[step] = seconds;
  const json j = {{"case", in.config->name},
                  {"config", in.config->file.string()},
                  {"pose_source", in.pose_source},
                  {"contact",
                   {{"band_mm", in.config->contact_band_mm},
                    {"area_mm2", o.contact_area_mm2},
                    {"spots", a.spots.size()},
                    {"samples", o.contact_samples},
                    {"min_distance_mm",
                     std::isfinite(o.min_distance_mm) ? json(o.min_distance_mm) : json(nullptr)},
                    {"left_share", o.left_share},
                    {"right_share", o.right_share},
                    {"anterior_share", o.anterior_share},
                    {"posterior_share", o.posterior_share}}},
                  {"penetration",
                   {{"max_mm", o.max_penetration_mm},
                    {"area_mm2", o.penetration_area_mm2},
                    {"allowed_mm", in.config->max_penetration_mm},
                    {"within_allowed", o.max_penetration_mm <= in.config->max_penetration_mm},
                    {"deepest_p_L", Vec(o.deepest_p_L)},
                    {"deep_samples", o.deep_samples}}},
                  {"teeth", teeth},
                  {"spots", spots},
                  {"relationships", RelationshipsJson(a.relationships)},
                  {"settings", Settings(*in.config, a)},
                  {"meshes",
                   {{"lower_triangles", in.jaws->lower_L->num_triangles()},
                    {"upper_triangles", in.jaws->upper_U->num_triangles()}}},
                  {"timings_s", timings}};
  json out = j;
  if (!in.search_json.empty()) out["search"] = json::parse(in.search_json);
  return out.dump(2) + "\n";
}

std::string PoseJson(const ReportInputs& in) {
  const ReportAnalysis& a = *in.analysis;
  const json j = {{"convention",
                   "X_LU: pose of the upper mesh's frame U (as loaded) in the lower jaw frame L, "
                   "mm. X_LU = T(pivot_U + "
                   "translation) R(rotation_deg) T(-pivot_U), rotation_deg a rotation vector in "
                   "degrees; pivot_L = X_LU pivot_U"},
                  {"X_LU", Matrix(a.X_LU.matrix())},
                  {"translation_mm", Vec(a.params.translation_mm)},
                  {"rotation_deg", Vec(a.params.rotation_deg)},
                  {"pivot_U_mm", Vec(a.X_LU.inverse() * a.pivot_L)},
                  {"pivot_L_mm", Vec(a.pivot_L)}};
  return j.dump(2) + "\n";
}

std::string ReportHtml(const ReportInputs& in) {
  const std::time_t now = std::time(nullptr);
  char stamp[64];
  std::strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  std::ostringstream s;
  s << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>Occlusion report: "
    << HtmlEscape(in.config->name) << "</title><style>" << kStyle << "</style></head><body>\n"
    << "<h1>Occlusion report: " << HtmlEscape(in.config->name)
    << "</h1>\n<p class=\"note\">occlude 0.1.0, " << stamp
    << ". Distances in mm; X<sub>LU</sub> is the pose of the upper jaw in the lower jaw's "
       "frame.</p>\n"
    << PoseSection(in) << MetricsSection(in) << RelationshipsHtml(in.analysis->relationships)
    << in.search_html;
  s << in.viewer_html << "<h2>Contact maps and views</h2>\n";
  for (const auto& p : in.pictures) {
    s << "<figure><img alt=\"" << HtmlEscape(p.title) << "\" src=\"data:image/png;base64,"
      << Base64(p.png) << "\"><figcaption class=\"note\">" << HtmlEscape(p.title) << " ("
      << HtmlEscape(p.file) << ")</figcaption></figure>\n";
  }
  s << TeethSection(in) << SettingsSection(in) << "</body></html>\n";
  return s.str();
}

}  // namespace occlude::app
