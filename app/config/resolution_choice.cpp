// Picking the oracle's voxel size and level from a measured table (see resolution_choice.h).
#include "config/resolution_choice.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/user_error.h"

namespace occlude::app {

extern const char* const kDefaultAccuracyTableJson;  // default_accuracy_table.cpp (generated)

namespace {

collision::AccuracyLevel LevelNamed(const std::string& name, const std::string& source) {
  if (name == "voxel") return collision::AccuracyLevel::kVoxel;
  if (name == "subvoxel") return collision::AccuracyLevel::kSubVoxel;
  if (name == "exact") return collision::AccuracyLevel::kExact;
  throw UserError(source + ": unknown oracle level \"" + name +
                  "\" (expected voxel, subvoxel or exact)");
}

std::string Num(double v) {
  std::ostringstream s;
  s.precision(v < 0.1 ? 2 : 3);
  s << v;
  return s.str();
}

}  // namespace

ResolutionTable ParseResolutionTable(const std::string& json_text, const std::string& source) {
  ResolutionTable table;
  table.source = source;
  try {
    const nlohmann::json j = nlohmann::json::parse(json_text);
    table.case_name = j.value("case", std::string());
    table.machine = j.value("machine", std::string());
    for (const nlohmann::json& row : j.at("oracle")) {
      if (row.value("method", std::string()) != "ist" || !row.at("voxel_mm").is_number()) continue;
      ResolutionOption o;
      o.voxel_mm = row.at("voxel_mm").get<double>();
      o.level = LevelNamed(row.at("level").get<std::string>(), source);
      o.median_us = row.at("median_us").get<double>();
      o.p95_err_mm = row.at("p95_err_mm").get<double>();
      o.max_err_mm = row.at("max_err_mm").get<double>();
      o.missed_half_band = row.value("missed_half_band", 0L);
      if (!(o.voxel_mm > 0.0) || !std::isfinite(o.median_us) || !std::isfinite(o.p95_err_mm))
        continue;
      table.options.push_back(o);
    }
  } catch (const nlohmann::json::exception& e) {
    throw UserError(source + ": not an accuracy table of `occlude bench --accuracy` (" +
                    std::string(e.what()) + "); give the accuracy-table.json it wrote");
  }
  if (table.options.empty()) {
    throw UserError(source +
                    ": the accuracy table has no IST oracle rows; give the accuracy-table.json of "
                    "`occlude bench --accuracy`");
  }
  std::stable_sort(table.options.begin(), table.options.end(),
                   [](const ResolutionOption& a, const ResolutionOption& b) {
                     return a.median_us < b.median_us;
                   });
  return table;
}

ResolutionTable LoadResolutionTable(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw UserError(file.string() + ": cannot read the accuracy table (accuracy.table)");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseResolutionTable(text.str(), file.string());
}

const ResolutionTable& DefaultResolutionTable() {
  static const ResolutionTable table = [] {
    ResolutionTable t = ParseResolutionTable(kDefaultAccuracyTableJson, "built-in table");
    t.source = "the table measured on " + t.case_name + " (built in)";
    return t;
  }();
  return table;
}

ResolutionChoice ChooseResolution(double accuracy_mm, const ResolutionTable& table) {
  ResolutionChoice c;
  c.accuracy_mm = accuracy_mm;
  c.source = table.source;
  for (const ResolutionOption& o : table.options) {  // fastest first
    if (o.p95_err_mm <= accuracy_mm && o.missed_half_band == 0) {
      c.chosen = o;
      return c;
    }
  }
  c.met = false;
  c.chosen = *std::min_element(table.options.begin(), table.options.end(),
                               [](const ResolutionOption& a, const ResolutionOption& b) {
                                 return a.p95_err_mm < b.p95_err_mm ||
                                        (a.p95_err_mm == b.p95_err_mm && a.median_us < b.median_us);
                               });
  return c;
}

ResolutionChoice ExplicitResolution(double voxel_mm, const ResolutionTable& table) {
  ResolutionChoice c;
  c.explicit_voxel = true;
  c.source = table.source;
  c.chosen.voxel_mm = voxel_mm;
  c.chosen.level = collision::AccuracyLevel::kSubVoxel;
  c.measured = false;
  for (const ResolutionOption& o : table.options) {
    if (o.level == c.chosen.level && std::abs(o.voxel_mm - voxel_mm) < 1e-9) {
      c.chosen = o;
      c.measured = true;
    }
  }
  return c;
}

std::string ResolutionChoice::Describe() const {
  std::string s = explicit_voxel ? "voxel " + Num(chosen.voxel_mm) + " mm (accuracy.voxel_mm)"
                                 : "accuracy " + Num(accuracy_mm) + " mm: voxel " +
                                       Num(chosen.voxel_mm) + " mm";
  s += std::string(" at ") + collision::ToString(chosen.level) + " level";
  if (measured) {
    s += " (measured 95th percentile error " + Num(chosen.p95_err_mm) + " mm, " +
         Num(chosen.median_us / 1000.0) + " ms per query, in " + source + ")";
  }
  if (!met)
    s += "; no measured setting reaches " + Num(accuracy_mm) + " mm: this is the most accurate one";
  return s;
}

}  // namespace occlude::app
