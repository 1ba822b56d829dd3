// STL writers (binary and ASCII), atomic: the bytes are built in memory after
// validating the mesh, then written beside the target and renamed over it. Also
// the checks and little-endian putters the PLY writer shares.
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "mesh_io_internal.h"
#include "mesh_io_text.h"

namespace occlude::io {
namespace detail {

namespace fs = std::filesystem;

void CheckWritable(const TriangleMesh& mesh, const fs::path& file) {
  if (mesh.triangles.empty()) Fail(file, "cannot write: the mesh has no triangles");
  const auto nv = static_cast<int>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    if ((tri.array() < 0).any() || (tri.array() >= nv).any()) {
      Fail(file, "cannot write: triangle " + std::to_string(t) + " indexes a vertex outside 0.." +
                     std::to_string(nv - 1));
    }
  }
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!mesh.vertices[v].allFinite()) {
      Fail(file, "cannot write: vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
  }
}

void CheckFitsFloat(const TriangleMesh& mesh, const fs::path& file, const char* format) {
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (mesh.vertices[v].cwiseAbs().maxCoeff() > static_cast<double>(FLT_MAX)) {
      Fail(file, "cannot write: vertex " + std::to_string(v) +
                     " does not fit a 32-bit float, which " + format + " stores");
    }
  }
}

void PutU32(std::uint32_t value, char* out) {
  for (int i = 0; i < 4; ++i) out[i] = static_cast<char>((value >> (8 * i)) & 0xffu);
}

void PutF32(float value, char* out) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  PutU32(bits, out);
}

namespace {

// Unit normal of triangle t from its corners (zero when degenerate).
Eigen::Vector3d NormalOf(const TriangleMesh& mesh, std::size_t t) {
  const Eigen::Vector3d n =
      (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

void PutVector(const Eigen::Vector3d& v, char* out) {
  for (int i = 0; i < 3; ++i) PutF32(static_cast<float>(v[i]), out + 4 * i);
}

std::string HeaderBytes(const std::string& header) {
  std::string_view text = header;
  std::string_view trimmed = text;
  while (!trimmed.empty() && IsSpace(trimmed.front())) trimmed.remove_prefix(1);
  std::string out = StartsWithNoCase(trimmed, "solid") ? "binary " + header : header;
  out.resize(kStlHeaderBytes, '\0');
  return out;
}

void AppendVector(const char* keyword, const Eigen::Vector3d& v, std::string& out) {
  out += keyword;
  for (int i = 0; i < 3; ++i) {
    out += ' ';
    out += FormatNumber(v[i]);
  }
  out += '\n';
}

}  // namespace

std::string EncodeBinaryStl(const TriangleMesh& mesh, const fs::path& file,
                            const std::string& header) {
  CheckWritable(mesh, file);
  if (mesh.triangles.size() > UINT32_MAX) {
    Fail(file, "cannot write: binary STL holds at most 4294967295 triangles");
  }
  CheckFitsFloat(mesh, file, "binary STL");
  std::string out = HeaderBytes(header);
  out.resize(kStlPreambleBytes + kStlRecordBytes * mesh.triangles.size(), '\0');
  PutU32(static_cast<std::uint32_t>(mesh.triangles.size()), out.data() + kStlHeaderBytes);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    char* record = out.data() + kStlPreambleBytes + kStlRecordBytes * t;
    PutVector(NormalOf(mesh, t), record);
    for (int k = 0; k < 3; ++k) PutVector(mesh.corner(t, k), record + 12 + 12 * k);
    // The 2-byte attribute stays zero.
  }
  return out;
}

std::string EncodeAsciiStl(const TriangleMesh& mesh, const fs::path& file) {
  CheckWritable(mesh, file);
  std::string out = "solid occlude\n";
  out.reserve(out.size() + 256 * mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    AppendVector("  facet normal", NormalOf(mesh, t), out);
    out += "    outer loop\n";
    for (int k = 0; k < 3; ++k) AppendVector("      vertex", mesh.corner(t, k), out);
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid occlude\n";
  return out;
}

}  // namespace detail

void WriteBinaryStl(const TriangleMesh& mesh, const std::filesystem::path& file,
                    const std::string& header) {
  detail::WriteFileAtomically(file, detail::EncodeBinaryStl(mesh, file, header));
}

void WriteAsciiStl(const TriangleMesh& mesh, const std::filesystem::path& file) {
  detail::WriteFileAtomically(file, detail::EncodeAsciiStl(mesh, file));
}

}  // namespace occlude::io
