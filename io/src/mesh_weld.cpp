// From a reader's RawMesh to the project's TriangleMesh: unit conversion to mm,
// degenerate-triangle removal, deterministic welding of identical positions,
// face normals, and the single part.
#include <cstdint>
#include <cstring>

#include "mesh_io_internal.h"
#include "mesh_io_text.h"
#include "occlude/io/content_hash.h"

namespace occlude::io::detail {
namespace {

namespace fs = std::filesystem;

// Coordinates beyond this (mm) are no scan in any unit (10^9 km); below it every
// cross product and squared area of a triangle stays finite in double.
constexpr double kMaxCoordinateMm = 1e15;

std::uint64_t Bits(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// -0.0 becomes +0.0, so that positions equal by value are equal in bits.
Eigen::Vector3d WithoutNegativeZero(Eigen::Vector3d p) {
  for (int i = 0; i < 3; ++i) {
    if (p[i] == 0.0) p[i] = 0.0;
  }
  return p;
}

// Open-addressing hash set of positions that appends each new position to
// `vertices` and returns its index: vertex order = order of first use.
class Welder {
 public:
  Welder(std::size_t expected_vertices, std::vector<Eigen::Vector3d>* vertices)
      : vertices_(*vertices) {
    std::size_t capacity = 16;
    while (capacity < 2 * expected_vertices) capacity *= 2;
    slots_.assign(capacity, -1);
  }

  int IndexOf(const Eigen::Vector3d& p) {
    if (2 * (vertices_.size() + 1) > slots_.size()) Grow();
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = Hash(p) & mask;; i = (i + 1) & mask) {
      const int id = slots_[i];
      if (id < 0) {
        slots_[i] = static_cast<int>(vertices_.size());
        vertices_.push_back(p);
        return slots_[i];
      }
      if (vertices_[static_cast<std::size_t>(id)] == p) return id;
    }
  }

 private:
  static std::uint64_t Hash(const Eigen::Vector3d& p) {
    return Mix64(Bits(p.x()) ^ Mix64(Bits(p.y()) ^ Mix64(Bits(p.z()))));
  }

  void Grow() {
    slots_.assign(2 * slots_.size(), -1);
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t id = 0; id < vertices_.size(); ++id) {
      std::size_t i = Hash(vertices_[id]) & mask;
      while (slots_[i] >= 0) i = (i + 1) & mask;
      slots_[i] = static_cast<int>(id);
    }
  }

  std::vector<int> slots_;
  std::vector<Eigen::Vector3d>& vertices_;
};

}  // namespace

TriangleMesh BuildMesh(const fs::path& file, RawMesh raw, double mm_per_unit, LoadReport& report) {
  report.vertices_before_weld += raw.positions.size();
  for (auto& warning : raw.warnings) report.warnings.push_back(std::move(warning));
  for (auto& p : raw.positions) p = WithoutNegativeZero(p * mm_per_unit);

  TriangleMesh mesh;
  mesh.triangles.reserve(raw.triangles.size());
  // A closed triangle mesh has about half as many vertices as triangles.
  Welder welder(raw.triangles.size() / 2, &mesh.vertices);
  std::size_t dropped = 0;
  for (const Eigen::Vector3i& tri : raw.triangles) {
    const Eigen::Vector3d& a = raw.positions[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector3d& b = raw.positions[static_cast<std::size_t>(tri[1])];
    const Eigen::Vector3d& c = raw.positions[static_cast<std::size_t>(tri[2])];
    if (!a.allFinite() || !b.allFinite() || !c.allFinite()) {
      Fail(file,
           "a vertex has a non-finite coordinate (NaN or infinity); the file is corrupt: "
           "export it again");
    }
    for (const Eigen::Vector3d* corner : {&a, &b, &c}) {
      const double largest = corner->cwiseAbs().maxCoeff();
      if (largest > kMaxCoordinateMm) {
        Fail(file, "a vertex coordinate of " + FormatNumber(largest) +
                       " mm is beyond the +-1e15 mm any scan "
                       "can hold; the file is corrupt (or its units are wrong)");
      }
    }
    // Zero area, including two identical corners (which welding would merge).
    if ((b - a).cross(c - a).squaredNorm() == 0.0) {
      ++dropped;
      continue;
    }
    // One statement each: the order of first use fixes the vertex numbering.
    const int ia = welder.IndexOf(a);
    const int ib = welder.IndexOf(b);
    const int ic = welder.IndexOf(c);
    mesh.triangles.emplace_back(ia, ib, ic);
  }
  report.degenerate_triangles_dropped += dropped;
  if (mesh.triangles.empty()) {
    Fail(file, dropped > 0 ? "all " + std::to_string(dropped) +
                                 " triangles are degenerate (zero area); there is no surface"
                           : std::string("contains no triangles"));
  }
  if (dropped > 0) {
    report.warnings.push_back(Line(file, "dropped " + std::to_string(dropped) +
                                             " degenerate (zero-area) triangles of " +
                                             std::to_string(raw.triangles.size())));
  }
  mesh.ComputeFaceNormals();
  const std::string stem = file.stem().string();
  mesh.parts.push_back({stem, ToothNumberFromFileName(stem)});
  mesh.triangle_part.assign(mesh.triangles.size(), 0);
  return mesh;
}

}  // namespace occlude::io::detail
