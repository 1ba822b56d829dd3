// Accuracy-driven resolution: the user states the distance accuracy wanted
// (`accuracy.accuracy_mm`) and occlude picks the voxel size and the accuracy level of the
// contact oracle from a measured speed-accuracy table (`occlude bench --accuracy` writes
// one, accuracy-table.json), instead of a hand-set voxel size.
//
// The table: the oracle rows of accuracy-table.json (voxel size, level, median query time,
// contact-distance error against exact triangle distances: median, 95th percentile, max;
// contacts within half the band missed). The default is the table measured on
// a-bite-3shape (docs/results/accuracy/a-bite-3shape), compiled in; `accuracy.table =
// "file.json"` uses another (for example one measured on a scanner's own data).
//
// The rule: the fastest row (median query time) whose 95th-percentile error is at most
// the wanted accuracy and which missed no contact within half the band. When no row
// meets the wanted accuracy, the most accurate row, flagged `met = false`.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "occlude/collision/oracle.h"

namespace occlude::app {

struct ResolutionOption {
  double voxel_mm = 0.0;
  collision::AccuracyLevel level = collision::AccuracyLevel::kSubVoxel;
  double median_us = 0.0;   ///< median oracle query time where it was measured
  double p95_err_mm = 0.0;  ///< 95th percentile of |contact distance - exact|
  double max_err_mm = 0.0;
  long missed_half_band = 0;  ///< contacts within delta/2 the level did not report
};

struct ResolutionTable {
  std::string source;  ///< "the table measured on a-bite-3shape (built in)" or the file
  std::string case_name, machine;
  std::vector<ResolutionOption> options;
};

/// Parses the oracle rows of an accuracy-table.json; UserError naming `source` when the
/// text is not such a table.
ResolutionTable ParseResolutionTable(const std::string& json_text, const std::string& source);
/// Reads and parses a table file; UserError naming the file.
ResolutionTable LoadResolutionTable(const std::filesystem::path& file);
/// The compiled-in table (measured on a-bite-3shape).
const ResolutionTable& DefaultResolutionTable();

struct ResolutionChoice {
  double accuracy_mm = 0.0;  ///< wanted (0 when the voxel size was set explicitly)
  bool explicit_voxel = false;
  bool met = true;          ///< a row met the wanted accuracy
  ResolutionOption chosen;  ///< voxel size and level in use; errors as measured (or 0 if unknown)
  bool measured = true;  ///< `chosen` has measured errors (false: explicit voxel not in the table)
  std::string source;    ///< the table's source
  /// One line for the user: "accuracy 0.02 mm: voxel 0.2 mm at sub-voxel level (measured
  /// 95th percentile error 0.012 mm, 2.3 ms per query on a-bite-3shape)".
  std::string Describe() const;
};

/// The rule above. `accuracy_mm` > 0.
ResolutionChoice ChooseResolution(double accuracy_mm, const ResolutionTable& table);
/// An explicit voxel size: sub-voxel level, with the measured errors of the table's row at
/// that voxel size when it has one.
ResolutionChoice ExplicitResolution(double voxel_mm, const ResolutionTable& table);

}  // namespace occlude::app
