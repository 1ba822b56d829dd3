// The coloured PLY writer (see coloured_ply.h): the bytes are built in memory
// after the same checks as the STL writers, then written atomically.
#include "occlude/io/coloured_ply.h"

#include <charconv>
#include <cmath>
#include <string>

#include "mesh_io_internal.h"

namespace occlude::io {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kVertexBytes = 3 * 4 + 3 + 4;
constexpr std::size_t kFaceBytes = 1 + 3 * 4;

void CheckValues(const TriangleMesh& mesh, const VertexValues& values, const fs::path& file) {
  detail::CheckWritable(mesh, file);
  detail::CheckFitsFloat(mesh, file, "PLY");
  const std::size_t n = mesh.vertices.size();
  if (values.rgb.size() != n || values.distance_mm.size() != n) {
    detail::Fail(file, "cannot write: " + std::to_string(values.rgb.size()) + " colours and " +
                           std::to_string(values.distance_mm.size()) + " distances for " +
                           std::to_string(n) + " vertices; give one of each per vertex");
  }
  for (std::size_t v = 0; v < n; ++v) {
    if (!std::isfinite(values.distance_mm[v])) {
      detail::Fail(file, "cannot write: the distance of vertex " + std::to_string(v) +
                             " is not finite; give a finite sentinel for unknown distances");
    }
  }
}

std::string Header(const TriangleMesh& mesh, PlyEncoding encoding) {
  return std::string("ply\nformat ") +
         (encoding == PlyEncoding::kAscii ? "ascii" : "binary_little_endian") +
         " 1.0\ncomment occlude: coordinates in mm; distance_mm is the signed distance to the "
         "opposing surface (negative = penetration)\nelement vertex " +
         std::to_string(mesh.vertices.size()) +
         "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty "
         "uchar green\nproperty uchar blue\nproperty float distance_mm\nelement face " +
         std::to_string(mesh.triangles.size()) +
         "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string BinaryBody(const TriangleMesh& mesh, const VertexValues& values) {
  std::string out(kVertexBytes * mesh.vertices.size() + kFaceBytes * mesh.triangles.size(), '\0');
  char* p = out.data();
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v, p += kVertexBytes) {
    for (int k = 0; k < 3; ++k) detail::PutF32(static_cast<float>(mesh.vertices[v][k]), p + 4 * k);
    for (int k = 0; k < 3; ++k) p[12 + k] = static_cast<char>(values.rgb[v][k]);
    detail::PutF32(values.distance_mm[v], p + 15);
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    p[0] = 3;
    for (int k = 0; k < 3; ++k) detail::PutU32(static_cast<std::uint32_t>(t[k]), p + 1 + 4 * k);
    p += kFaceBytes;
  }
  return out;
}

// The shortest decimal that reads back as the same float.
void AppendFloat(float value, std::string& out) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

std::string AsciiBody(const TriangleMesh& mesh, const VertexValues& values) {
  std::string out;
  out.reserve(64 * mesh.vertices.size() + 24 * mesh.triangles.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    for (int k = 0; k < 3; ++k) {
      AppendFloat(static_cast<float>(mesh.vertices[v][k]), out);
      out += ' ';
    }
    for (int k = 0; k < 3; ++k) out += std::to_string(values.rgb[v][k]) + ' ';
    AppendFloat(values.distance_mm[v], out);
    out += '\n';
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    out += "3 " + std::to_string(t[0]) + ' ' + std::to_string(t[1]) + ' ' + std::to_string(t[2]) +
           '\n';
  }
  return out;
}

}  // namespace

void WriteColouredPly(const TriangleMesh& mesh, const VertexValues& values, const fs::path& file,
                      PlyEncoding encoding) {
  CheckValues(mesh, values, file);
  const std::string body =
      encoding == PlyEncoding::kAscii ? AsciiBody(mesh, values) : BinaryBody(mesh, values);
  detail::WriteFileAtomically(file, Header(mesh, encoding) + body);
}

}  // namespace occlude::io
