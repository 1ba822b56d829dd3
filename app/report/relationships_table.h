// The clinical relationships as a reader sees them: one row per measure (overjet, overbite,
// midline, molar and canine relationship per side, posterior crossbite) with its value, the
// normal range of ../shared/docs/clinical.md and whether the value lies outside it; the
// "Clinical relationships" section of report.html; and the before -> after lines `refine` prints.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/relationships.h"

namespace occlude::app {

struct RelationshipRow {
  std::string name;          ///< "overjet", "molar relationship, right", ...
  std::optional<double> mm;  ///< the value; nullopt for crossbite and for what was not found
  std::string value;         ///< as shown: "2.70 mm", "0.19 mm (Class I)", "none", "not found"
  std::string normal;        ///< the normal range, e.g. "1 to 3 mm"
  bool outside = false;      ///< a value outside the normal range
  std::string reason;        ///< why a value is missing or partial (empty when complete)
};

/// The rows, in clinical.md's order.
std::vector<RelationshipRow> RelationshipRows(const analysis::Relationships& r);

/// The report section: a heading, the frame the measures are taken in and the table (outside
/// values marked, missing ones shown as "not found" with the reason).
std::string RelationshipsHtml(const analysis::Relationships& r);

/// One line per measure: "overjet: 2.70 mm -> 3.05 mm" (with "(outside 1 to 3 mm)" after a
/// value outside its range).
std::vector<std::string> RelationshipChanges(const analysis::Relationships& before,
                                             const analysis::Relationships& after);

}  // namespace occlude::app
