// Private to occlude::io: the pieces LoadMesh is built from (file reading,
// format readers, welding, atomic writing). Not installed, no assimp types.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "occlude/io/atomic_file.h"
#include "occlude/io/mesh_io.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::io::detail {

// Binary STL layout, shared by the reader and the writer: an 80-byte header, a uint32 triangle
// count, then per triangle a 50-byte record (normal, 3 vertices: 12 floats, a uint16).
constexpr std::size_t kStlHeaderBytes = 80;
constexpr std::size_t kStlPreambleBytes = kStlHeaderBytes + 4;
constexpr std::size_t kStlRecordBytes = 50;

/// Triangles as a format reader delivers them: file units, file corner order,
/// not yet checked for finiteness (except where the reader says so) nor welded.
struct RawMesh {
  std::vector<Eigen::Vector3d> positions;  ///< file units
  std::vector<Eigen::Vector3i> triangles;  ///< indices into `positions`, in range
  std::vector<std::string> warnings;       ///< complete lines, beginning with the path
};

/// Throws MeshError "<file>: <what>", folded onto one line.
[[noreturn]] void Fail(const std::filesystem::path& file, const std::string& what);
/// "<file>: <what>", folded onto one line (for warnings).
std::string Line(const std::filesystem::path& file, const std::string& what);

/// The whole file, after checking it exists, is a readable non-empty regular
/// file of sane size. Throws MeshError otherwise.
std::string ReadWholeFile(const std::filesystem::path& file);

/// WriteFileAtomically (atomic_file.h), as the writers here call it.
using io::WriteFileAtomically;

/// STL, binary or ASCII (decided by content); coordinates checked finite.
RawMesh ReadStl(const std::filesystem::path& file, std::string_view bytes);
/// OBJ: validated and reduced to canonical text, then imported by assimp. A
/// UTF-8 byte-order mark is skipped (also for PLY and ASCII STL).
RawMesh ReadObj(const std::filesystem::path& file, std::string_view bytes);
/// PLY: header and every body value validated, re-encoded as canonical binary
/// PLY, then imported by assimp.
RawMesh ReadPly(const std::filesystem::path& file, std::string_view bytes);

/// Structural checks run before assimp sees the bytes, so that assimp never
/// gets out-of-range indices, non-finite coordinates, counts the file does not
/// back, or truncated data. Throw MeshError naming the line or element.
///
/// The OBJ check also returns what assimp is given: the file reduced to
/// "v x y z" and "f i j k ..." lines (absolute 1-based vertex indices). assimp
/// 5.2's OBJ parser crashes on some malformed lines (e.g. a line "a" after
/// "mtllib") and opens material libraries relative to the working directory;
/// geometry is all occlude needs.
std::string CanonicalObjText(const std::filesystem::path& file, std::string_view text);
/// The PLY check likewise returns a canonical binary PLY of the walked vertices
/// (float x, y, z) and faces, whatever the file's format and element layout;
/// notes on what it leaves out go to `warnings`.
std::string CanonicalPlyBytes(const std::filesystem::path& file, std::string_view bytes,
                              std::vector<std::string>* warnings);

/// assimp import (triangulated) of an OBJ or PLY held in memory; `hint` is the
/// extension without dot. Drops point/line primitives with a warning.
RawMesh ImportWithAssimp(const std::filesystem::path& file, std::string_view bytes,
                         const char* hint);

/// Converts `raw` to a welded TriangleMesh in mm (one part named after the file
/// stem): scales by `mm_per_unit`, rejects non-finite coordinates, drops
/// zero-area triangles, welds identical positions in first-use order, computes
/// face normals. Fills `report` (counts added, warnings appended). Throws
/// MeshError when no triangle is left.
TriangleMesh BuildMesh(const std::filesystem::path& file, RawMesh raw, double mm_per_unit,
                       LoadReport& report);

/// Refuses what no mesh file can hold: no triangles, indices outside the
/// vertices, non-finite coordinates. Throws MeshError naming `file`.
void CheckWritable(const TriangleMesh& mesh, const std::filesystem::path& file);
/// Refuses coordinates beyond the float range; `format` names what stores floats.
void CheckFitsFloat(const TriangleMesh& mesh, const std::filesystem::path& file,
                    const char* format);
/// Little-endian 32-bit values into out[0..3].
void PutU32(std::uint32_t value, char* out);
void PutF32(float value, char* out);

/// Binary and ASCII STL file contents for `mesh` (validated; throws MeshError
/// naming `file`).
std::string EncodeBinaryStl(const TriangleMesh& mesh, const std::filesystem::path& file,
                            const std::string& header);
std::string EncodeAsciiStl(const TriangleMesh& mesh, const std::filesystem::path& file);

}  // namespace occlude::io::detail
