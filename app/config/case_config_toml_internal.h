// Typed, checked access to one TOML table of a case file (private to occlude::config: the case
// config, the plan config and the clinical targets read their tables through it). Every failure
// is a UserError of the form `<file>:<line>: <table.key>: <what is wrong>`, so the user finds the
// key at once.
#pragma once

#include <toml++/toml.h>

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace occlude::app::toml_config {

/// `text` with every control character written as an escape ("\n", "\x01"), so
/// that a message quoting keys or values from the file stays one line.
std::string OneLine(const std::string& text);

/// The text of a config file. Throws UserError: "<file>: no such config file", "<file>: is a
/// folder; give the case's .toml file" or "<file>: cannot read the config file: <why>".
std::string ReadConfigText(const std::filesystem::path& file);

/// `text` parsed as TOML; `abs_file` names it in the error "<file>:<line>: not valid TOML: ...".
toml::table ParseText(const std::string& text, const std::filesystem::path& abs_file);

/// The key of `candidates` `word` most likely meant: one it abbreviates (or that abbreviates
/// it) first, then the fewest edits (empty if there are no candidates).
std::string ClosestKey(const std::string& word, const std::vector<std::string>& candidates);

class Table {
 public:
  /// `path` is the table's dotted path ("" for the root), `file` the config file.
  Table(const toml::table& table, std::string path, std::filesystem::path file);

  /// Fails on the first key not in `allowed`, suggesting the closest allowed one
  /// (or `extra_suggestions`, dotted keys elsewhere in the file, when closer).
  void AllowOnly(const std::vector<std::string>& allowed,
                 const std::vector<std::string>& extra_suggestions = {}) const;

  bool Has(const std::string& key) const { return table_.contains(key); }
  std::optional<Table> SubTable(const std::string& key) const;

  /// A number in [lo, hi] (bounds exclusive when the flag says so); `rule` is the
  /// constraint as the message states it ("a length in mm in (0, 5]").
  std::optional<double> Number(const std::string& key, double lo, bool lo_open, double hi,
                               bool hi_open, const std::string& rule) const;
  std::optional<std::int64_t> Integer(const std::string& key, std::int64_t lo,
                                      std::int64_t hi) const;
  std::optional<std::string> String(const std::string& key) const;
  std::optional<bool> Bool(const std::string& key) const;
  std::optional<std::vector<std::string>> StringArray(const std::string& key) const;
  /// An array of exactly `n` finite numbers.
  std::optional<std::vector<double>> NumberArray(const std::string& key, std::size_t n,
                                                 const std::string& rule) const;
  std::optional<Eigen::Matrix4d> Matrix4(const std::string& key) const;
  /// A path string resolved against the config file's folder (lexically normal).
  std::optional<std::filesystem::path> Path(const std::string& key) const;
  /// The resolved path of element i of a string array (for error messages: key[i]).
  std::filesystem::path Resolve(const std::string& text) const;

  /// Throws UserError at the key's line: "<file>:<line>: <path.key>: <what>".
  [[noreturn]] void Fail(const std::string& key, const std::string& what) const;
  std::string KeyPath(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  const toml::table& raw() const { return table_; }

 private:
  const toml::node* Node(const std::string& key) const { return table_.get(key); }
  const toml::table& table_;
  std::string path_;
  std::filesystem::path file_;
};

/// "an integer", "a string", ... for messages.
std::string TypeName(const toml::node& node);

}  // namespace occlude::app::toml_config
