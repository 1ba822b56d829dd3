// Checked TOML table access for case files (see case_config_toml_internal.h).
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "base/user_error.h"
#include "config/case_config.h"
#include "config/case_config_toml_internal.h"
#include "config/pose_file.h"

namespace occlude::app::toml_config {

std::string ReadConfigText(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw UserError(file.string() + ": no such config file");
  if (std::filesystem::is_directory(file, ec)) {
    throw UserError(file.string() + ": is a folder; give the case's .toml file");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    const int error = errno;
    throw UserError(file.string() + ": cannot read the config file: " + std::strerror(error) +
                    (error == EACCES ? "; check the file's permissions" : ""));
  }
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

toml::table ParseText(const std::string& text, const std::filesystem::path& abs_file) {
  try {
    return toml::parse(text, abs_file.string());
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << abs_file.string() << ":" << e.source().begin.line
      << ": not valid TOML: " << e.description();
    throw UserError(OneLine(s.str()));
  }
}

std::string OneLine(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[u >> 4];
      out += hex[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

namespace {

// Whether every character of `short_word` appears in `long_word` in order ("memory_mb" in
// "memory_budget_mb"): an abbreviation, which a plain edit distance ranks below unrelated keys
// of similar length ("cache_mb").
// Only for a short word of 3 characters or more and at least half the long one, so that "tz"
// or "mode" does not abbreviate every longer key.
bool IsSubsequence(const std::string& short_word, const std::string& long_word) {
  if (short_word.size() < 3 || 2 * short_word.size() < long_word.size()) return false;
  std::size_t i = 0;
  for (std::size_t j = 0; i < short_word.size() && j < long_word.size(); ++j) {
    if (short_word[i] == long_word[j]) ++i;
  }
  return i == short_word.size();
}

}  // namespace

std::string ClosestKey(const std::string& word, const std::vector<std::string>& candidates) {
  // Abbreviations (either way) first, then the fewest edits.
  std::string best;
  std::pair<bool, std::size_t> best_rank{true, std::numeric_limits<std::size_t>::max()};
  for (const auto& c : candidates) {
    const bool abbreviation = IsSubsequence(word, c) || IsSubsequence(c, word);
    const std::pair<bool, std::size_t> rank{!abbreviation, EditDistance(word, c)};
    if (rank < best_rank) {
      best_rank = rank;
      best = c;
    }
  }
  return best;
}

std::string TypeName(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    default:
      return "a date/time";
  }
}

Table::Table(const toml::table& table, std::string path, std::filesystem::path file)
    : table_(table), path_(std::move(path)), file_(std::move(file)) {}

void Table::Fail(const std::string& key, const std::string& what) const {
  const toml::node* n = key.empty() ? nullptr : Node(key);
  std::ostringstream s;
  s << file_.string();
  const auto line = n != nullptr ? n->source().begin.line : table_.source().begin.line;
  if (line > 0) s << ":" << line;
  s << ": "
    << (key.empty() ? (path_.empty() ? std::string("(root)") : "[" + path_ + "]") : KeyPath(key))
    << ": " << what;
  throw UserError(OneLine(s.str()));
}

void Table::AllowOnly(const std::vector<std::string>& allowed,
                      const std::vector<std::string>& extra_suggestions) const {
  for (auto&& [k, node] : table_) {
    const std::string key(k.str());
    bool ok = false;
    for (const auto& a : allowed) ok = ok || a == key;
    if (ok) continue;
    std::string hint = ClosestKey(key, allowed);
    std::string hint_path = KeyPath(hint);
    // A key misplaced from another table: compare with the last part of "table.key".
    std::string extra;
    std::size_t extra_d = std::numeric_limits<std::size_t>::max();
    for (const auto& e : extra_suggestions) {
      const std::size_t d = EditDistance(key, e.substr(e.rfind('.') + 1));
      if (d < extra_d) {
        extra_d = d;
        extra = e;
      }
    }
    if (!extra.empty() && (hint.empty() || extra_d < EditDistance(key, hint))) hint_path = extra;
    std::ostringstream s;
    s << file_.string() << ":" << k.source().begin.line << ": " << KeyPath(key) << ": unknown key";
    if (!hint.empty() || !extra.empty()) s << "; did you mean '" << hint_path << "'?";
    throw UserError(OneLine(s.str()));
  }
}

std::optional<Table> Table::SubTable(const std::string& key) const {
  const toml::node* n = Node(key);
  if (n == nullptr) return std::nullopt;
  if (!n->is_table()) Fail(key, "must be a table ([" + KeyPath(key) + "]), got " + TypeName(*n));
  return Table(*n->as_table(), KeyPath(key), file_);
}

std::optional<double> Table::Number(const std::string& key, double lo, bool lo_open, double hi,
                                    bool hi_open, const std::string& rule) const {
  const toml::node* n = Node(key);
  if (n == nullptr) return std::nullopt;
  if (!n->is_number()) Fail(key, "must be " + rule + ", got " + TypeName(*n));
  const double v = *n->value<double>();
  const bool ok = std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  if (!ok) {
    std::ostringstream s;
    s << "must be " << rule << ", got " << v;
    Fail(key, s.str());
  }
  return v;
}

std::optional<std::int64_t> Table::Integer(const std::string& key, std::int64_t lo,
                                           std::int64_t hi) const {
  const toml::node* n = Node(key);
  if (n == nullptr) return std::nullopt;
  std::ostringstream rule;
  rule << "an integer in [" << lo << ", " << hi << "]";
  if (!n->is_integer()) Fail(key, "must be " + rule.str() + ", got " + TypeName(*n));
  const std::int64_t v = n->as_integer()->get();
  if (v < lo || v > hi) Fail(key, "must be " + rule.str() + ", got " + std::to_string(v));
  return v;
}

std::optional<bool> Table::Bool(const std::string& key) const {
  const toml::node* n = Node(key);
  if (n == nullptr) return std::nullopt;
  if (!n->is_boolean()) Fail(key, "must be true or false, got " + TypeName(*n));
  return n->as_boolean()->get();
}

std::optional<std::string> Table::String(const std::string& key) const {
  const toml::node* n = Node(key);
  if (n == nullptr) return std::nullopt;
  if (!n->is_string()) Fail(key, "must be a string, got " + TypeName(*n));
  return n->as_string()->get();
}

std::optional<std::vector<std::string>> Table::StringArray(const std::string& key) const {
  const toml::node* n = Node(key);
  if (n == nullptr) return std::nullopt;
  if (!n->is_array()) Fail(key, "must be an array of strings, got " + TypeName(*n));
  std::vector<std::string> out;
  for (const toml::node& e : *n->as_array()) {
    if (!e.is_string()) Fail(key, "must be an array of strings, has " + TypeName(e));
    out.push_back(e.as_string()->get());
  }
  return out;
}

std::optional<std::vector<double>> Table::NumberArray(const std::string& key, std::size_t n_wanted,
                                                      const std::string& rule) const {
  const toml::node* n = Node(key);
  if (n == nullptr) return std::nullopt;
  const toml::array* a = n->as_array();
  if (a == nullptr || a->size() != n_wanted) Fail(key, "must be " + rule);
  std::vector<double> out;
  for (const toml::node& e : *a) {
    if (!e.is_number()) Fail(key, "must be " + rule + ", has " + TypeName(e));
    const double v = *e.value<double>();
    if (!std::isfinite(v)) Fail(key, "must be " + rule + " (finite), has " + std::to_string(v));
    out.push_back(v);
  }
  return out;
}

std::optional<Eigen::Matrix4d> Table::Matrix4(const std::string& key) const {
  const toml::node* n = Node(key);
  if (n == nullptr) return std::nullopt;
  const std::string rule = "a 4x4 rigid matrix: 4 rows of 4 numbers, last row [0, 0, 0, 1]";
  const toml::array* rows = n->as_array();
  if (rows == nullptr || rows->size() != 4) Fail(key, "must be " + rule);
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    const toml::array* row = rows->get(static_cast<std::size_t>(r))->as_array();
    if (row == nullptr || row->size() != 4) Fail(key, "must be " + rule);
    for (int c = 0; c < 4; ++c) {
      const toml::node* e = row->get(static_cast<std::size_t>(c));
      if (!e->is_number()) Fail(key, "must be " + rule + ", has " + TypeName(*e));
      m(r, c) = *e->value<double>();
    }
  }
  const std::string err = RigidTransformError(m);
  if (!err.empty()) Fail(key, err);
  return m;
}

std::filesystem::path Table::Resolve(const std::string& text) const {
  std::filesystem::path p(text);
  if (p.is_relative()) p = file_.parent_path() / p;
  return p.lexically_normal();
}

std::optional<std::filesystem::path> Table::Path(const std::string& key) const {
  const auto text = String(key);
  if (!text) return std::nullopt;
  if (text->empty()) Fail(key, "must be a non-empty path");
  return Resolve(*text);
}

}  // namespace occlude::app::toml_config
