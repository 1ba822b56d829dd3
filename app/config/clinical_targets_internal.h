// Reading the [clinical] table of a case config (used by case_config.cpp; see
// clinical_targets.h for the keys).
#pragma once

#include "config/case_config_toml_internal.h"
#include "config/clinical_targets.h"

namespace occlude::app {

/// The targets of a [clinical] table (only its keys). Throws UserError naming the key for an
/// unknown key, a class name not I/II/III, a class given both for both sides and for one, an
/// empty interval, a negative midline limit or an unknown mode.
ClinicalTargets ReadClinicalTable(const toml_config::Table& t);

}  // namespace occlude::app
