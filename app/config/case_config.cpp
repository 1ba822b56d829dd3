// Case configuration files: reading and validating every table (see
// case_config.h for the keys, units and defaults).
#include "config/case_config.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/axis_name.h"
#include "base/user_error.h"
#include "config/case_config_toml_internal.h"
#include "config/clinical_targets_internal.h"
#include "occlude/io/synthetic_jaws.h"

namespace occlude::app {
namespace {

using toml_config::Table;

const std::vector<std::string> kRootTables = {
    "case",  "lower",  "upper",  "synthetic", "accuracy", "contact", "solver",    "bounds",
    "start", "adjust", "output", "report",    "limits",   "refine",  "landmarks", "clinical"};
const std::vector<std::string> kDofNames = {"tx", "ty", "tz", "rx", "ry", "rz"};
const std::vector<std::string> kBoundKeys = {"tx_mm",  "ty_mm",  "tz_mm", "rx_deg",
                                             "ry_deg", "rz_deg", "locked"};

// Every "table.key" of the format, so a misplaced key at the root can point to its table.
std::vector<std::string> AllDottedKeys() {
  return {"case.name",
          "case.units",
          "case.up_axis",
          "lower.file",
          "lower.parts",
          "upper.file",
          "upper.parts",
          "synthetic.triangles",
          "synthetic.seed",
          "accuracy.accuracy_mm",
          "accuracy.voxel_mm",
          "accuracy.sample_spacing_mm",
          "accuracy.table",
          "accuracy.region_of_interest",
          "contact.band_mm",
          "contact.max_penetration_mm",
          "solver.name",
          "solver.starts",
          "solver.seed",
          "solver.threads",
          "solver.proposals",
          "solver.max_seconds",
          "solver.scope",
          "solver.options",
          "solver.global",
          "bounds.tx_mm",
          "bounds.ty_mm",
          "bounds.tz_mm",
          "bounds.rx_deg",
          "bounds.ry_deg",
          "bounds.rz_deg",
          "bounds.locked",
          "start.translation_mm",
          "start.rotation_deg",
          "start.matrix",
          "start.pivot_mm",
          "adjust.translation_mm",
          "adjust.rotation_deg",
          "output.folder",
          "report.map_max_mm",
          "report.map_penetration_from_mm",
          "report.image_width_px",
          "limits.memory_budget_mb",
          "limits.cache_mb",
          "refine.hold",
          "landmarks.file",
          "clinical.molar_class",
          "clinical.molar_class_right",
          "clinical.molar_class_left",
          "clinical.canine_class",
          "clinical.canine_class_right",
          "clinical.canine_class_left",
          "clinical.overjet_mm",
          "clinical.overbite_mm",
          "clinical.midline_max_mm",
          "clinical.mode"};
}

std::optional<Eigen::Vector3d> ParseUpAxis(const Table& t, const std::string& text) {
  if (text == "auto") return std::nullopt;
  const std::optional<Eigen::Vector3d> axis = AxisFromName(text);
  if (!axis) {
    t.Fail("up_axis",
           "'" + text +
               "' is not an axis; use \"auto\", \"+x\", \"-x\", \"+y\", \"-y\", \"+z\" or \"-z\"");
  }
  return axis;
}

void ReadCase(const Table& t, CaseConfig* c) {
  t.AllowOnly({"name", "units", "up_axis"});
  if (auto v = t.String("name")) c->name = *v;
  if (auto v = t.String("units")) {
    const auto unit = io::ParseLengthUnit(*v);
    if (!unit) t.Fail("units", "unknown unit '" + *v + "'; use mm, cm, m, um or in");
    c->units = *unit;
  }
  if (auto v = t.String("up_axis")) c->up_axis_L = ParseUpAxis(t, *v);
}

void CheckFile(const Table& t, const std::string& key, const std::filesystem::path& p) {
  std::error_code ec;
  if (!std::filesystem::exists(p, ec)) {
    t.Fail(key,
           "no such file '" + p.string() + "' (relative paths start at the config file's folder)");
  }
  if (!std::filesystem::is_regular_file(p, ec)) t.Fail(key, "'" + p.string() + "' is not a file");
}

JawFiles ReadJaw(const Table& t) {
  t.AllowOnly({"file", "parts"});
  JawFiles jaw;
  if (t.Has("file") == t.Has("parts")) {
    t.Fail("", "give exactly one of file = \"jaw.stl\" or parts = [\"Tooth_N.stl\", ...]");
  }
  if (auto p = t.Path("file")) {
    CheckFile(t, "file", *p);
    jaw.files = {*p};
    return jaw;
  }
  const auto parts = *t.StringArray("parts");
  if (parts.empty())
    t.Fail("parts", "is empty; list the part files (one per tooth, plus the gingiva)");
  jaw.parts = true;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const auto p = t.Resolve(parts[i]);
    CheckFile(t, "parts[" + std::to_string(i) + "]", p);
    jaw.files.push_back(p);
  }
  return jaw;
}

void ReadSynthetic(const Table& t, CaseConfig* c) {
  t.AllowOnly({"triangles", "seed"});
  SyntheticSource s;
  if (auto v = t.Integer("triangles", static_cast<std::int64_t>(io::kMinSyntheticTriangles),
                         static_cast<std::int64_t>(io::kMaxSyntheticTriangles))) {
    s.triangles = static_cast<std::size_t>(*v);
  }
  if (auto v = t.Integer("seed", 0, 0xffffffffLL)) s.seed = static_cast<std::uint32_t>(*v);
  c->synthetic = s;
}

void ReadAccuracy(const Table& t, CaseConfig* c) {
  t.AllowOnly({"accuracy_mm", "voxel_mm", "sample_spacing_mm", "table", "region_of_interest"});
  if (auto v = t.Number("accuracy_mm", 0, true, 1, false, "a positive length in mm, at most 1")) {
    c->accuracy_mm = *v;
  }
  c->voxel_mm = t.Number("voxel_mm", 0, true, 5, false, "a positive voxel size in mm, at most 5");
  if (auto v =
          t.Number("sample_spacing_mm", 0, true, 5, false, "a positive spacing in mm, at most 5")) {
    c->sample_spacing_mm = *v;
  }
  if (auto v = t.Bool("region_of_interest")) c->region_of_interest = *v;
  if (auto p = t.Path("table")) {
    CheckFile(t, "table", *p);
    c->accuracy_table = *p;
  }
  const ResolutionTable table =
      c->accuracy_table ? LoadResolutionTable(*c->accuracy_table) : DefaultResolutionTable();
  c->resolution = c->voxel_mm ? ExplicitResolution(*c->voxel_mm, table)
                              : ChooseResolution(c->accuracy_mm, table);
}

void ReadContact(const Table& t, CaseConfig* c) {
  t.AllowOnly({"band_mm", "max_penetration_mm"});
  if (auto v = t.Number("band_mm", 0, true, 5, false, "a band in mm in (0, 5]"))
    c->contact_band_mm = *v;
  if (auto v = t.Number("max_penetration_mm", 0, false, 5, false, "a depth in mm in [0, 5]")) {
    c->max_penetration_mm = *v;
  }
}

// [solver.global]: the global search's scan.
void ReadSolverGlobal(const Table& g, SolverSettings* s) {
  g.AllowOnly({"sagittal_step_mm", "max_basins", "max_refined"});
  s->global_sagittal_step_mm =
      g.Number("sagittal_step_mm", 0, true, 15, false, "a step in mm in (0, 15]");
  if (auto v = g.Integer("max_basins", 1, 1000)) s->global_max_basins = static_cast<int>(*v);
  if (auto v = g.Integer("max_refined", 1, 1000)) s->global_max_refined = static_cast<int>(*v);
}

void ReadSolver(const Table& t, CaseConfig* c) {
  t.AllowOnly({"name", "starts", "seed", "threads", "proposals", "max_seconds", "scope", "options",
               "global"});
  SolverSettings& s = c->solver;
  if (auto v = t.String("name")) {
    if (v->empty()) t.Fail("name", "must name a solver (or \"auto\")");
    s.name = *v;
  }
  if (auto v = t.Integer("starts", 1, 100000)) s.starts = static_cast<int>(*v);
  if (auto v = t.Integer("seed", 0, std::numeric_limits<std::int64_t>::max())) {
    s.seed = static_cast<std::uint64_t>(*v);
  }
  if (auto v = t.Integer("threads", 0, 1024)) s.threads = static_cast<int>(*v);
  if (auto v = t.Integer("proposals", 1, 1000)) s.proposals = static_cast<int>(*v);
  if (auto v = t.Number("max_seconds", 0, true, 1e6, false, "a positive number of seconds")) {
    s.max_seconds = *v;
  }
  if (auto v = t.String("scope")) {
    if (*v != "local" && *v != "global")
      t.Fail("scope", "'" + *v + "' is not a scope; use \"local\" or \"global\"");
    s.scope = *v;
  }
  if (auto g = t.SubTable("global")) ReadSolverGlobal(*g, &s);
  if (auto o = t.SubTable("options")) {
    for (auto&& [k, node] : o->raw()) {
      const std::string key(k.str());
      if (node.is_boolean()) {
        s.options[key] = node.as_boolean()->get();
      } else if (node.is_integer()) {
        s.options[key] = node.as_integer()->get();
      } else if (node.is_floating_point()) {
        s.options[key] = node.as_floating_point()->get();
      } else if (node.is_string()) {
        s.options[key] = node.as_string()->get();
      } else {
        o->Fail(key, "must be a boolean, number or string, got " + toml_config::TypeName(node));
      }
    }
  }
}

// The degrees of freedom named in t[key] (an error naming the key for an unknown name).
std::array<bool, kNumDofs> DofMask(const Table& t, const std::string& key,
                                   const std::vector<std::string>& names) {
  std::array<bool, kNumDofs> mask{};
  for (const auto& name : names) {
    const auto it = std::find(kDofNames.begin(), kDofNames.end(), name);
    if (it == kDofNames.end()) {
      t.Fail(key, "'" + name +
                      "' is not a degree of freedom; use tx, ty, tz, rx, ry, rz (did you mean '" +
                      toml_config::ClosestKey(name, kDofNames) + "'?)");
    }
    mask[static_cast<std::size_t>(it - kDofNames.begin())] = true;
  }
  return mask;
}

void ReadBounds(const Table& t, CaseConfig* c) {
  t.AllowOnly(kBoundKeys);
  for (int d = 0; d < kNumDofs; ++d) {
    const std::string& key = kBoundKeys[static_cast<std::size_t>(d)];
    const bool rot = d >= 3;
    const std::string rule =
        rot ? "[min, max] in degrees within [-180, 180]" : "[min, max] in mm within [-100, 100]";
    const auto v = t.NumberArray(key, 2, rule);
    if (!v) continue;
    const double limit = rot ? 180.0 : 100.0;
    if (std::abs((*v)[0]) > limit || std::abs((*v)[1]) > limit) t.Fail(key, "must be " + rule);
    if ((*v)[0] > (*v)[1]) {
      std::ostringstream s;
      s << "min " << (*v)[0] << " is greater than max " << (*v)[1]
        << "; write [min, max] with min <= max";
      t.Fail(key, s.str());
    }
    c->bounds[static_cast<std::size_t>(d)] = {(*v)[0], (*v)[1]};
  }
  if (auto locked = t.StringArray("locked")) {
    c->locked = DofMask(t, "locked", *locked);
    if (std::all_of(c->locked.begin(), c->locked.end(), [](bool b) { return b; })) {
      t.Fail("locked", "all six degrees of freedom are locked; leave at least one free");
    }
  }
}

Eigen::Vector3d Vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

void ReadPoseParams(const Table& t, planner::PoseParameters* p) {
  if (auto v = t.NumberArray("translation_mm", 3, "[x, y, z] in mm")) p->translation_mm = Vec3(*v);
  if (auto v = t.NumberArray("rotation_deg", 3, "[x, y, z] in degrees (a rotation vector)")) {
    p->rotation_deg = Vec3(*v);
    if (p->rotation_deg.norm() > 180.0)
      t.Fail("rotation_deg",
             "rotation angle over 180 degrees; give a rotation vector of at most 180 degrees");
  }
}

void ReadStart(const Table& t, CaseConfig* c) {
  t.AllowOnly({"translation_mm", "rotation_deg", "matrix", "pivot_mm"});
  if (t.Has("matrix") && (t.Has("translation_mm") || t.Has("rotation_deg"))) {
    t.Fail("matrix", "give either matrix or translation_mm/rotation_deg, not both");
  }
  c->start.matrix = t.Matrix4("matrix");
  ReadPoseParams(t, &c->start.params);
  if (auto v = t.NumberArray("pivot_mm", 3, "[x, y, z] in mm")) c->start.pivot_mm = Vec3(*v);
}

void ReadReport(const Table& t, CaseConfig* c) {
  t.AllowOnly({"map_max_mm", "map_penetration_from_mm", "image_width_px"});
  if (auto v = t.Number("map_max_mm", 0, true, 5, false, "a length in mm in (0, 5]"))
    c->report.map_max_mm = *v;
  if (auto v = t.Number("map_penetration_from_mm", 0, false, 1, false, "a depth in mm in [0, 1]")) {
    c->report.map_penetration_from_mm = *v;
  }
  if (auto v = t.Integer("image_width_px", 300, 4000))
    c->report.image_width_px = static_cast<int>(*v);
}

// [refine] hold = "adjusted" | "none" | ["tx", ...].
void ReadRefine(const Table& t, CaseConfig* c) {
  t.AllowOnly({"hold"});
  const toml::node* hold = t.raw().get("hold");
  if (hold == nullptr) return;
  if (hold->is_array()) {
    c->refine.hold_adjusted = false;
    c->refine.hold = DofMask(t, "hold", *t.StringArray("hold"));
    return;
  }
  const std::optional<std::string> mode = hold->is_string() ? t.String("hold") : std::nullopt;
  if (mode != "adjusted" && mode != "none") {
    t.Fail("hold",
           "give \"adjusted\" (hold what [adjust] changes), \"none\" (let every free degree of "
           "freedom settle) or a list of degrees of freedom such as [\"tx\", \"rz\"]");
  }
  c->refine.hold_adjusted = *mode == "adjusted";
  c->refine.hold = {};
}

void ReadLandmarks(const Table& t, CaseConfig* c) {
  t.AllowOnly({"file"});
  c->landmarks_file = t.Path("file");
  if (c->landmarks_file) CheckFile(t, "file", *c->landmarks_file);
}

void ReadAll(const Table& root, CaseConfig* c) {
  root.AllowOnly(kRootTables, AllDottedKeys());
  if (auto t = root.SubTable("case")) ReadCase(*t, c);
  if (auto t = root.SubTable("lower")) c->lower = ReadJaw(*t);
  if (auto t = root.SubTable("upper")) c->upper = ReadJaw(*t);
  if (auto t = root.SubTable("synthetic")) ReadSynthetic(*t, c);
  if (c->synthetic && (c->lower || c->upper)) {
    root.Fail("synthetic",
              "a case uses either [synthetic] or [lower]/[upper] mesh files, not both");
  }
  if (!c->synthetic && (!c->lower || !c->upper)) {
    root.Fail(
        c->lower ? "upper" : "lower",
        "missing; give [lower] and [upper] (file = ... or parts = [...]) or a [synthetic] table");
  }
  if (auto t = root.SubTable("accuracy")) ReadAccuracy(*t, c);
  if (auto t = root.SubTable("contact")) ReadContact(*t, c);
  if (auto t = root.SubTable("solver")) ReadSolver(*t, c);
  if (auto t = root.SubTable("bounds")) ReadBounds(*t, c);
  if (auto t = root.SubTable("start")) ReadStart(*t, c);
  if (auto t = root.SubTable("adjust")) {
    t->AllowOnly({"translation_mm", "rotation_deg"});
    ReadPoseParams(*t, &c->adjust);
  }
  if (auto t = root.SubTable("output")) {
    t->AllowOnly({"folder"});
    c->output_dir = t->Path("folder");
  }
  if (auto t = root.SubTable("report")) ReadReport(*t, c);
  if (auto t = root.SubTable("refine")) ReadRefine(*t, c);
  if (auto t = root.SubTable("landmarks")) ReadLandmarks(*t, c);
  if (auto t = root.SubTable("clinical")) c->clinical = ReadClinicalTable(*t);
  if (auto t = root.SubTable("limits")) {
    t->AllowOnly({"memory_budget_mb", "cache_mb"});
    c->memory_budget_mb =
        t->Number("memory_budget_mb", 0, true, 1e9, false, "a positive number of megabytes");
    c->cache_mb = t->Number("cache_mb", 0, false, 1e9, false, "a number of megabytes, 0 or more")
                      .value_or(c->cache_mb);
  }
  if (c->report.map_max_mm < c->contact_band_mm) {
    root.Fail("report",
              "map_max_mm must be at least contact.band_mm so contacts are on the colour scale");
  }
}

}  // namespace

const char* DofName(int dof) {
  static const char* const kNames[] = {"tx", "ty", "tz", "rx", "ry", "rz"};
  return dof >= 0 && dof < kNumDofs ? kNames[dof] : "?";
}

double CaseConfig::VoxelSizeMm() const { return resolution.chosen.voxel_mm; }

std::size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

CaseConfig ParseCaseConfig(const std::string& text, const std::filesystem::path& file) {
  const std::filesystem::path abs = std::filesystem::absolute(file).lexically_normal();
  const toml::table root = toml_config::ParseText(text, abs);
  CaseConfig c;
  c.file = abs;
  c.name = abs.stem().string();
  ReadAll(Table(root, "", abs), &c);
  return c;
}

CaseConfig LoadCaseConfig(const std::filesystem::path& file) {
  return ParseCaseConfig(toml_config::ReadConfigText(file), file);
}

Eigen::Isometry3d StartPoseOf(const CaseConfig& config, const Eigen::Vector3d& default_pivot_L) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (config.start.matrix) {
    X.matrix() = *config.start.matrix;
    return X;
  }
  return planner::ComposePose(config.start.params, config.start.pivot_mm.value_or(default_pivot_L),
                              X);
}

}  // namespace occlude::app
