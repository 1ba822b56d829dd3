// The clinical relationships (analysis/relationships.h) as JSON, one schema for analysis.json,
// metrics.json and proposals.json: overjet_mm, overbite_mm, midline_deviation_mm, molar_mm and
// canine_mm {right, left}, molar_class and canine_class {right, left} ("I", "II", "III"),
// crossbite [FDI]; a value that could not be measured is null, with the reason beside it
// (`<measure>_reason`, for sides {right, left} with null where there is none). Also
// frame_source ("landmarks" or "lower arch"), molar_end_on / canine_end_on {right, left} and
// crossbite_unchecked [FDI] (upper teeth lacking a landmark for the check).
#pragma once

#include <nlohmann/json.hpp>

#include "analysis/relationships.h"

namespace occlude::app {

nlohmann::json RelationshipsJson(const analysis::Relationships& r);

/// The frame the relationships are measured in: {origin_L, lateral, anterior, occlusal} (mm and
/// unit vectors in L), or null when there is none.
nlohmann::json RelationshipFrameJson(const analysis::Relationships& r);

}  // namespace occlude::app
