// The landmark file: hand-placed (or exported) landmarks of both jaws as CSV, the format of the
// c-cases' `landmarks.csv` (../shared/docs/clinical.md):
//
//   jaw,tooth,type,x_mm,y_mm,z_mm
//   upper,17,mesial,-28.146921,-1.616967,-15.811103
//
// `jaw` is "upper" or "lower", `tooth` an FDI number of that jaw, `type` a landmark type name
// (occlude/io/dental.h), coordinates finite millimetres in the frame of that jaw's mesh. Blank
// lines are skipped; "\r\n" line ends and a UTF-8 byte-order mark are accepted.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "occlude/io/dental.h"

namespace occlude::io {

/// A landmark file that cannot be read. The message is one line: the file, the line number
/// when there is one, the field, what is wrong and the fix.
class LandmarkFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The header line a landmark file starts with.
inline constexpr std::string_view kLandmarkFileHeader = "jaw,tooth,type,x_mm,y_mm,z_mm";

/// Every landmark of `file`, in file order. Throws LandmarkFileError for a missing or unreadable
/// file, a wrong header, a row with a missing or extra column, an unknown jaw, tooth (not FDI,
/// or not of that jaw) or type, a coordinate that is not a finite number, and a landmark given
/// twice (same jaw, tooth and type).
std::vector<Landmark> ReadLandmarkFile(const std::filesystem::path& file);

/// The same on the file's text already in memory; `file` only names it in messages.
std::vector<Landmark> ParseLandmarkFile(std::string_view text, const std::filesystem::path& file);

/// The text of a landmark file holding `landmarks` in order: the header, then one row each,
/// coordinates to 1e-6 mm. ParseLandmarkFile reads it back.
std::string FormatLandmarkFile(const std::vector<Landmark>& landmarks);

}  // namespace occlude::io
