// The [clinical] table of a case config (see clinical_targets.h).
#include <cmath>
#include <sstream>

#include "base/user_error.h"
#include "config/clinical_targets_internal.h"

namespace occlude::app {
namespace {

const std::vector<std::string> kClinicalKeys = {"molar_class",        "molar_class_right",
                                                "molar_class_left",   "canine_class",
                                                "canine_class_right", "canine_class_left",
                                                "overjet_mm",         "overbite_mm",
                                                "midline_max_mm",     "mode"};

std::string ClassName(const toml_config::Table& t, const std::string& key,
                      const std::string& value) {
  if (value != "I" && value != "II" && value != "III") {
    t.Fail(key, "'" + value + "' is not a class; use \"I\", \"II\" or \"III\"");
  }
  return value;
}

// `<name>_class` for both sides or `<name>_class_right` / `_left` for one.
std::array<std::optional<std::string>, 2> ReadSides(const toml_config::Table& t,
                                                    const std::string& name) {
  const std::string both = name + "_class", right = both + "_right", left = both + "_left";
  std::array<std::optional<std::string>, 2> sides;
  if (auto v = t.String(both)) {
    if (t.Has(right) || t.Has(left)) {
      t.Fail(both, "given with " + (t.Has(right) ? right : left) + "; give either " + both +
                       " (both sides) or the per-side keys");
    }
    sides[0] = sides[1] = ClassName(t, both, *v);
  }
  if (auto v = t.String(right)) sides[0] = ClassName(t, right, *v);
  if (auto v = t.String(left)) sides[1] = ClassName(t, left, *v);
  return sides;
}

std::optional<MmInterval> ReadInterval(const toml_config::Table& t, const std::string& key) {
  const std::string rule = "[min, max] in mm within [-20, 20]";
  const auto v = t.NumberArray(key, 2, rule);
  if (!v) return std::nullopt;
  if (std::abs((*v)[0]) > 20.0 || std::abs((*v)[1]) > 20.0) t.Fail(key, "must be " + rule);
  if ((*v)[0] > (*v)[1]) {
    std::ostringstream s;
    s << "[" << (*v)[0] << ", " << (*v)[1]
      << "] is an empty interval; write [min, max] with min <= max";
    t.Fail(key, s.str());
  }
  return MmInterval{(*v)[0], (*v)[1]};
}

}  // namespace

const char* ToString(ClinicalTargets::Mode mode) {
  return mode == ClinicalTargets::Mode::kConstraint ? "constraint" : "rank";
}

ClinicalTargets ReadClinicalTable(const toml_config::Table& t) {
  t.AllowOnly(kClinicalKeys);
  ClinicalTargets c;
  c.from_config = true;
  c.molar_class = ReadSides(t, "molar");
  c.canine_class = ReadSides(t, "canine");
  c.overjet_mm = ReadInterval(t, "overjet_mm");
  c.overbite_mm = ReadInterval(t, "overbite_mm");
  c.midline_max_mm =
      t.Number("midline_max_mm", 0, false, 20, false, "a deviation in mm in [0, 20]");
  if (auto v = t.String("mode")) {
    if (*v == "constraint")
      c.mode = ClinicalTargets::Mode::kConstraint;
    else if (*v != "rank")
      t.Fail("mode", "'" + *v + "' is not a mode; use \"rank\" or \"constraint\"");
  }
  return c;
}

ClinicalTargets LoadClinicalTargets(const std::filesystem::path& file) {
  const std::filesystem::path abs = std::filesystem::absolute(file).lexically_normal();
  const toml::table root = toml_config::ParseText(toml_config::ReadConfigText(file), abs);
  const auto table = toml_config::Table(root, "", abs).SubTable("clinical");
  if (!table) {
    throw UserError(file.string() +
                    ": no [clinical] table; give one, e.g. [clinical] molar_class = \"I\"");
  }
  return ReadClinicalTable(*table);
}

}  // namespace occlude::app
