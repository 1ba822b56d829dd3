// Public mesh loading: format dispatch, jaws from part files, the units sanity
// check, tooth numbers from file names, and length units.
#include "occlude/io/mesh_io.h"

#include <array>
#include <charconv>
#include <map>
#include <utility>

#include "mesh_io_internal.h"
#include "mesh_io_text.h"

namespace occlude::io {
namespace {

namespace fs = std::filesystem;

// A plausible jaw (a whole arch or a single tooth crown) measured in mm.
constexpr double kSmallestJawMm = 5.0;
constexpr double kLargestJawMm = 500.0;

constexpr std::array<LengthUnit, 5> kAllUnits = {LengthUnit::kMillimetre, LengthUnit::kCentimetre,
                                                 LengthUnit::kMetre, LengthUnit::kMicrometre,
                                                 LengthUnit::kInch};

std::string Lowered(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

// About 4 significant digits, locale-independent: "0.06", "1.235e+04".
std::string Approx(double value) {
  char buffer[32];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 4);
  return std::string(buffer, result.ptr);
}

std::string_view LongName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre:
      return "millimetres";
    case LengthUnit::kCentimetre:
      return "centimetres";
    case LengthUnit::kMetre:
      return "metres";
    case LengthUnit::kMicrometre:
      return "micrometres";
    case LengthUnit::kInch:
      return "inches";
  }
  return "?";
}

detail::RawMesh ReadByExtension(const fs::path& file, std::string_view bytes) {
  const std::string extension = Lowered(file.extension().string());
  if (extension == ".stl") return detail::ReadStl(file, bytes);
  if (extension == ".obj") return detail::ReadObj(file, bytes);
  if (extension == ".ply") return detail::ReadPly(file, bytes);
  detail::Fail(file, (extension.empty() ? std::string("has no file extension")
                                        : "unsupported file type '" + extension + "'") +
                         "; occlude reads .stl, .obj and .ply files");
}

// One file, one part, no units check.
TriangleMesh LoadOne(const fs::path& file, const LoadOptions& options, LoadReport& report) {
  const std::string bytes = detail::ReadWholeFile(file);
  return detail::BuildMesh(file, ReadByExtension(file, bytes), MillimetresPer(options.unit),
                           report);
}

// Warns when the largest extent is outside what a jaw can measure in mm, naming
// the units that would bring it into range.
void CheckUnits(const std::string& subject, const TriangleMesh& mesh, LengthUnit unit,
                LoadReport& report) {
  const double extent = mesh.Bounds().sizes().maxCoeff();
  if (extent >= kSmallestJawMm && extent <= kLargestJawMm) return;
  std::string what = "the largest extent is " + Approx(extent) + " mm, too " +
                     (extent < kSmallestJawMm ? "small" : "large") + " for a jaw (" +
                     Approx(kSmallestJawMm) + " to " + Approx(kLargestJawMm) + " mm expected)";
  const double in_file_units = extent / MillimetresPer(unit);
  std::string fixes;
  for (const LengthUnit candidate : kAllUnits) {
    const double mm = in_file_units * MillimetresPer(candidate);
    if (candidate == unit || mm < kSmallestJawMm || mm > kLargestJawMm) continue;
    fixes += std::string(fixes.empty() ? "" : " or ") + std::string(LongName(candidate)) +
             " (set units = \"" + std::string(LengthUnitName(candidate)) + "\")";
  }
  what += fixes.empty() ? "; check the file's units" : "; it looks like " + fixes;
  report.warnings.push_back(subject + ": " + what);
}

}  // namespace

double MillimetresPer(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre:
      return 1.0;
    case LengthUnit::kCentimetre:
      return 10.0;
    case LengthUnit::kMetre:
      return 1000.0;
    case LengthUnit::kMicrometre:
      return 0.001;
    case LengthUnit::kInch:
      return 25.4;
  }
  return 1.0;
}

std::string_view LengthUnitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre:
      return "mm";
    case LengthUnit::kCentimetre:
      return "cm";
    case LengthUnit::kMetre:
      return "m";
    case LengthUnit::kMicrometre:
      return "um";
    case LengthUnit::kInch:
      return "in";
  }
  return "?";
}

std::optional<LengthUnit> ParseLengthUnit(std::string_view name) {
  constexpr std::pair<std::string_view, LengthUnit> kNames[] = {
      {"mm", LengthUnit::kMillimetre},
      {"millimetre", LengthUnit::kMillimetre},
      {"millimeter", LengthUnit::kMillimetre},
      {"cm", LengthUnit::kCentimetre},
      {"centimetre", LengthUnit::kCentimetre},
      {"centimeter", LengthUnit::kCentimetre},
      {"m", LengthUnit::kMetre},
      {"metre", LengthUnit::kMetre},
      {"meter", LengthUnit::kMetre},
      {"um", LengthUnit::kMicrometre},
      {"micrometre", LengthUnit::kMicrometre},
      {"micrometer", LengthUnit::kMicrometre},
      {"micron", LengthUnit::kMicrometre},
      {"in", LengthUnit::kInch},
      {"inch", LengthUnit::kInch},
      {"inches", LengthUnit::kInch}};
  std::string key = Lowered(name);
  if (key.size() > 2 && key.back() == 's' && key != "inches") key.pop_back();  // plurals
  for (const auto& [known, unit] : kNames) {
    if (key == known) return unit;
  }
  return std::nullopt;
}

int ToothNumberFromFileName(const std::string& stem) {
  std::string_view rest = stem;
  if (detail::StartsWithNoCase(rest, "tooth")) rest.remove_prefix(5);
  while (!rest.empty() && (rest[0] == '_' || rest[0] == '-' || rest[0] == ' ' || rest[0] == '.')) {
    rest.remove_prefix(1);
  }
  if (rest.empty() || rest.size() > 3) return 0;
  int number = 0;
  for (const char c : rest) {
    if (c < '0' || c > '9') return 0;
    number = 10 * number + (c - '0');
  }
  return number >= 1 && number <= 32 ? number : 0;
}

TriangleMesh LoadMesh(const fs::path& file, const LoadOptions& options, LoadReport* report) {
  LoadReport local;
  LoadReport& out = report != nullptr ? *report : local;
  TriangleMesh mesh = LoadOne(file, options, out);
  CheckUnits(file.string(), mesh, options.unit, out);
  return mesh;
}

TriangleMesh LoadMeshFromBytes(std::string_view bytes, const fs::path& name,
                               const LoadOptions& options, LoadReport* report) {
  LoadReport local;
  LoadReport& out = report != nullptr ? *report : local;
  if (bytes.empty()) detail::Fail(name, "the file is empty (0 bytes); export the mesh again");
  TriangleMesh mesh =
      detail::BuildMesh(name, ReadByExtension(name, bytes), MillimetresPer(options.unit), out);
  CheckUnits(name.string(), mesh, options.unit, out);
  return mesh;
}

TriangleMesh LoadJawParts(const std::vector<JawPartFile>& files, const LoadOptions& options,
                          LoadReport* report) {
  if (files.empty()) throw MeshError("(no files): no jaw part files were given; list at least one");
  LoadReport local;
  LoadReport& out = report != nullptr ? *report : local;
  TriangleMesh jaw;
  std::map<int, fs::path> tooth_files;
  for (const JawPartFile& part_file : files) {
    TriangleMesh part = LoadOne(part_file.file, options, out);
    MeshPart& part_info = part.parts.front();
    if (!part_file.name.empty()) part_info.name = part_file.name;
    if (part_file.tooth_number >= 0) part_info.tooth_number = part_file.tooth_number;
    const int tooth = part_info.tooth_number;
    if (tooth > 0 && !tooth_files.emplace(tooth, part_file.file).second) {
      out.warnings.push_back(detail::Line(
          part_file.file,
          "tooth " + std::to_string(tooth) + " already came from " + tooth_files[tooth].string()));
    }
    jaw.Append(part);
  }
  const std::string subject = files.size() == 1
                                  ? files.front().file.string()
                                  : files.front().file.string() + " (+" +
                                        std::to_string(files.size() - 1) + " more part files)";
  CheckUnits(subject, jaw, options.unit, out);
  return jaw;
}

TriangleMesh LoadJawParts(const std::vector<fs::path>& files, const LoadOptions& options,
                          LoadReport* report) {
  std::vector<JawPartFile> parts;
  parts.reserve(files.size());
  for (const fs::path& file : files) parts.push_back({file, "", -1});
  return LoadJawParts(parts, options, report);
}

}  // namespace occlude::io
