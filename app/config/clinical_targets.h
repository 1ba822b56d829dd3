// The clinical targets of a case config ([clinical]): the molar and canine class per side, the
// overjet and overbite intervals and the largest midline deviation the surgeon asks for, and
// whether they rank the global search's seats (mode = "rank") or exclude the seats that break
// one (mode = "constraint"). Without a [clinical] table the targets are the default ranking of
// ../shared/docs/clinical.md's normal ranges: Class I molars and canines on both sides,
// overjet and overbite in [1, 3] mm, midline within 2 mm. With a table only its keys are
// targets. Keys:
//   molar_class = "I" | "II" | "III"  (both sides)  or  molar_class_right, molar_class_left
//   canine_class (same, with canine_class_right / canine_class_left)
//   overjet_mm = [min, max]; overbite_mm = [min, max]   (mm, min <= max, within [-20, 20])
//   midline_max_mm = 1                                  (mm, >= 0)
//   mode = "rank" (default) | "constraint"
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace occlude::app {

struct MmInterval {
  double min = 0.0;
  double max = 0.0;
};

struct ClinicalTargets {
  enum class Mode { kRank, kConstraint };
  Mode mode = Mode::kRank;
  /// True when the config had a [clinical] table (else these are the defaults).
  bool from_config = false;
  /// Angle's class names "I", "II", "III"; [0] the patient's right, [1] the left (as
  /// analysis::Relationships); nullopt = no target on that side.
  std::array<std::optional<std::string>, 2> molar_class{{"I", "I"}};
  std::array<std::optional<std::string>, 2> canine_class{{"I", "I"}};
  std::optional<MmInterval> overjet_mm = MmInterval{1.0, 3.0};
  std::optional<MmInterval> overbite_mm = MmInterval{1.0, 3.0};
  std::optional<double> midline_max_mm = 2.0;
};

/// "rank" or "constraint".
const char* ToString(ClinicalTargets::Mode mode);

/// The [clinical] table of a TOML file (a case config or a file holding only that table; its
/// other tables are not read). Throws UserError naming the file: not found, not TOML, no
/// [clinical] table, or a key of the table wrong (as in a case config).
ClinicalTargets LoadClinicalTargets(const std::filesystem::path& file);

}  // namespace occlude::app
