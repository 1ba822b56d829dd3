// Mesh files in and out: STL (binary and ASCII), OBJ and PLY into a welded
// TriangleMesh in millimetres, jaws assembled from per-tooth part files, and
// atomic STL writers.
//
// Every file is validated before it is trusted (sizes and counts before any
// allocation, every index and coordinate before assimp or the welder uses it),
// so a corrupt, truncated or hostile file fails with a MeshError (one line,
// beginning with the file path, saying what is wrong and how to fix it when
// there is a fix) rather than a crash, a hang or an absurd allocation.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::io {

/// Length unit of the coordinates stored in a file.
enum class LengthUnit { kMillimetre, kCentimetre, kMetre, kMicrometre, kInch };

/// How many millimetres one `unit` is (e.g. 1000 for kMetre, 25.4 for kInch).
double MillimetresPer(LengthUnit unit);
/// The short name used in configuration files: "mm", "cm", "m", "um", "in".
std::string_view LengthUnitName(LengthUnit unit);
/// Parses a unit name, case-insensitively: the short names above plus
/// "millimetre(s)", "centimetre(s)", "metre(s)", "micrometre(s)", "inch(es)"
/// and the -er spellings. nullopt when unknown.
std::optional<LengthUnit> ParseLengthUnit(std::string_view name);

struct LoadOptions {
  /// Unit of the file's coordinates; vertices are converted to millimetres.
  /// After conversion, vertices with identical coordinates (-0 equal to +0) are
  /// merged into one (welding); nothing else is merged.
  LengthUnit unit = LengthUnit::kMillimetre;
};

/// What a load noticed without failing. Counts are added to and warnings
/// appended, so one report can collect several loads.
struct LoadReport {
  std::vector<std::string> warnings;  ///< each one line, beginning with the file path
  /// Zero-area triangles (including those with two identical corners) removed.
  std::size_t degenerate_triangles_dropped = 0;
  /// Vertex records delivered by the file reader before welding (3 per triangle
  /// for STL, the OBJ/PLY vertex count as imported otherwise).
  std::size_t vertices_before_weld = 0;
};

/// Any failure to read or write a mesh file. The message is one line: the file
/// path, what is wrong and, when there is one, the fix.
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Loads one mesh file (.stl binary or ASCII, .obj, .ply; chosen by extension,
/// any case; binary vs ASCII STL by content). Result: welded vertices in mm in
/// the file's frame, numbered in order of first use; triangles in file order
/// (an OBJ/PLY polygon becomes several triangles in its place) keeping the
/// file's corner order (CCW = outward); face normals recomputed from the
/// corners (file normals are ignored); one MeshPart named after the file stem
/// with tooth_number from ToothNumberFromFileName. Degenerate triangles are
/// dropped (warning); a largest extent outside 5..500 mm gives a units warning
/// naming the fitting `units` setting. STL is read by occlude itself (binary:
/// float coordinates exactly; ASCII: correctly rounded doubles); OBJ and PLY
/// are validated by occlude, then imported by assimp (float precision).
/// Throws MeshError.
TriangleMesh LoadMesh(const std::filesystem::path& file, const LoadOptions& options = {},
                      LoadReport* report = nullptr);

/// LoadMesh on bytes already in memory (the same readers, checks and result);
/// `name` stands for the file: its extension picks the format, and messages and
/// the part name use it. Nothing is read from disk. Throws MeshError.
TriangleMesh LoadMeshFromBytes(std::string_view bytes, const std::filesystem::path& name,
                               const LoadOptions& options = {}, LoadReport* report = nullptr);

/// One part file of a jaw, with optional overrides of what the name implies.
struct JawPartFile {
  std::filesystem::path file;
  std::string name;       ///< part name; empty = the file stem
  int tooth_number = -1;  ///< Universal 1..32, 0 = not a tooth; -1 = from the file name
};

/// A jaw from several part files (e.g. a 3Shape export: Tooth_N.stl per tooth
/// plus Tooth_UpperJaw.stl for the gingiva), all in the same frame and unit.
/// Each file becomes one MeshPart, in the given order; vertices are welded
/// within a part, never across parts. The units check looks at the whole jaw.
/// Throws MeshError naming the first file that fails, or when `files` is empty.
TriangleMesh LoadJawParts(const std::vector<JawPartFile>& files, const LoadOptions& options = {},
                          LoadReport* report = nullptr);
/// Same, with each part named after its file stem and numbered from it.
TriangleMesh LoadJawParts(const std::vector<std::filesystem::path>& files,
                          const LoadOptions& options = {}, LoadReport* report = nullptr);

/// Universal tooth number (1..32) from a file stem, else 0. Accepts an optional
/// "tooth" prefix (any case) and separators '_', '-', ' ', '.' before the
/// number: "Tooth_14" -> 14, "tooth-3" -> 3, "Tooth_08" -> 8, "14" -> 14;
/// "Tooth_UpperJaw" -> 0, "upper" -> 0, "Tooth_33" -> 0, "Tooth_14_v2" -> 0.
int ToothNumberFromFileName(const std::string& stem);

/// Writes binary STL with float coordinates in mm (the mesh's values rounded to
/// float; exact when they are float-representable) and normals recomputed from
/// the corners. `header` fills the 80-byte header (truncated; a header starting
/// with "solid" gets "binary " in front so that readers do not take the file for
/// ASCII STL). Atomic: written to a temporary file in the same folder, then
/// renamed over `file`, so a failure never leaves a half-written file. Throws
/// MeshError naming the path (folder missing or not writable, empty or
/// inconsistent mesh, non-finite or out-of-float-range coordinates).
void WriteBinaryStl(const TriangleMesh& mesh, const std::filesystem::path& file,
                    const std::string& header = "occlude");

/// Writes ASCII STL ("solid occlude"), each coordinate as the shortest decimal
/// that reads back as the same double, so LoadMesh returns exactly the written
/// vertices. Same atomic behaviour and errors as WriteBinaryStl.
void WriteAsciiStl(const TriangleMesh& mesh, const std::filesystem::path& file);

}  // namespace occlude::io
