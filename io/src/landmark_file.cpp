// The landmark file reader (occlude/io/landmark_file.h): one pass over the lines, each row
// split at commas and checked field by field, so that every error names its line and column.
#include "occlude/io/landmark_file.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include "mesh_io_text.h"

namespace occlude::io {
namespace {

constexpr std::array<const char*, 6> kColumns = {"jaw", "tooth", "type", "x_mm", "y_mm", "z_mm"};

[[noreturn]] void Fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw LandmarkFileError(file.string() + (line > 0 ? ": line " + std::to_string(line) : "") +
                          ": " + what);
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && detail::IsSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && detail::IsSpace(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> SplitCommas(std::string_view line) {
  std::vector<std::string_view> fields;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(
        Trim(line.substr(start, comma == std::string_view::npos ? comma : comma - start)));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

void CheckHeader(std::string_view line, const std::filesystem::path& file, int number) {
  const std::vector<std::string_view> fields = SplitCommas(line);
  bool ok = fields.size() == kColumns.size();
  for (std::size_t i = 0; ok && i < fields.size(); ++i) ok = fields[i] == kColumns[i];
  if (!ok) {
    Fail(file, number,
         "header: " + detail::Quote(line) +
             " is not the landmark header; the first line must be '" +
             std::string(kLandmarkFileHeader) + "'");
  }
}

int ParseTooth(std::string_view token, Jaw jaw, const std::filesystem::path& file, int line) {
  long long value = 0;
  if (!detail::ParseInt(token, &value) || !IsValidFdi(static_cast<int>(value)) ||
      value != static_cast<int>(value)) {
    Fail(file, line,
         "tooth: " + detail::Quote(token) +
             " is not an FDI tooth number; use 11-18, 21-28 (upper), 31-38, 41-48 (lower)");
  }
  const int fdi = static_cast<int>(value);
  if (JawOfFdi(fdi) != jaw) {
    Fail(file, line,
         "tooth: " + std::to_string(fdi) + " is a" + (jaw == Jaw::kUpper ? " lower" : "n upper") +
             " tooth but jaw is '" + ToString(jaw) + "'; fix the jaw or the tooth number");
  }
  return fdi;
}

double ParseCoordinate(std::string_view token, int column, const std::filesystem::path& file,
                       int line) {
  double value = 0.0;
  if (!detail::ParseReal(token, &value) || !std::isfinite(value)) {
    Fail(file, line,
         std::string(kColumns[static_cast<std::size_t>(column)]) + ": " + detail::Quote(token) +
             " is not a finite number (millimetres)");
  }
  return value;
}

Landmark ParseRow(const std::vector<std::string_view>& fields, const std::filesystem::path& file,
                  int line) {
  if (fields.size() < kColumns.size()) {
    Fail(file, line,
         std::string(kColumns[fields.size()]) + ": missing column (" +
             std::to_string(fields.size()) + " of 6 fields); each row is '" +
             std::string(kLandmarkFileHeader) + "'");
  }
  if (fields.size() > kColumns.size()) {
    Fail(file, line,
         std::to_string(fields.size()) + " fields, expected 6 ('" +
             std::string(kLandmarkFileHeader) + "'); remove the extra columns");
  }
  Landmark l;
  const std::optional<Jaw> jaw = JawFromName(std::string(fields[0]));
  if (!jaw) Fail(file, line, "jaw: " + detail::Quote(fields[0]) + " is not 'upper' or 'lower'");
  l.jaw = *jaw;
  l.tooth_fdi = ParseTooth(fields[1], l.jaw, file, line);
  const std::optional<LandmarkType> type = LandmarkTypeFromName(std::string(fields[2]));
  if (!type) {
    Fail(file, line,
         "type: " + detail::Quote(fields[2]) + " is not a landmark type; use one of " +
             LandmarkTypeNames());
  }
  l.type = *type;
  for (int k = 0; k < 3; ++k) l.p[k] = ParseCoordinate(fields[3 + k], 3 + k, file, line);
  return l;
}

}  // namespace

std::vector<Landmark> ParseLandmarkFile(std::string_view text, const std::filesystem::path& file) {
  detail::LineReader lines(detail::WithoutUtf8Bom(text));
  std::string_view line;
  bool header_seen = false;
  std::vector<Landmark> landmarks;
  std::map<std::tuple<Jaw, int, LandmarkType>, int> first_line;
  while (lines.Next(&line)) {
    const int number = lines.line_number();
    if (Trim(line).empty()) continue;
    if (!header_seen) {
      CheckHeader(Trim(line), file, number);
      header_seen = true;
      continue;
    }
    const Landmark l = ParseRow(SplitCommas(line), file, number);
    const auto [it, fresh] =
        first_line.emplace(std::make_tuple(l.jaw, l.tooth_fdi, l.type), number);
    if (!fresh) {
      Fail(file, number,
           std::string("landmark ") + ToString(l.jaw) + " " + std::to_string(l.tooth_fdi) + " " +
               ToString(l.type) + " is given twice (first on line " + std::to_string(it->second) +
               "); keep one");
    }
    landmarks.push_back(l);
  }
  if (!header_seen) {
    Fail(file, 0,
         "the file is empty; a landmark file starts with the line '" +
             std::string(kLandmarkFileHeader) + "'");
  }
  return landmarks;
}

std::vector<Landmark> ReadLandmarkFile(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec)) {
    Fail(file, 0, "is a folder; name the landmark file (e.g. landmarks.csv)");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    Fail(file, 0,
         std::filesystem::exists(file, ec) ? "cannot be opened for reading; check its permissions"
                                           : "no such file; check the landmark file's path");
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) Fail(file, 0, "could not be read to the end");
  return ParseLandmarkFile(bytes.str(), file);
}

std::string FormatLandmarkFile(const std::vector<Landmark>& landmarks) {
  std::string text = std::string(kLandmarkFileHeader) + "\n";
  char row[160];
  for (const Landmark& l : landmarks) {
    std::snprintf(row, sizeof row, "%s,%d,%s,%.6f,%.6f,%.6f\n", ToString(l.jaw), l.tooth_fdi,
                  ToString(l.type), l.p.x(), l.p.y(), l.p.z());
    text += row;
  }
  return text;
}

}  // namespace occlude::io
