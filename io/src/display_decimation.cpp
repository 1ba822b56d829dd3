// Vertex clustering for display (see display_decimation.h): the cell size is
// searched geometrically, each cell of a part keeps the original vertex that
// best fits its planes, and the triangles spanning three cells survive.
#include "occlude/io/display_decimation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "decimation_code_hash.h"
#include "occlude/io/content_hash.h"

namespace occlude::io {
namespace {

/// Bisection steps of the cell size between a feasible and an infeasible one:
/// 2^(1/2^10), i.e. within 0.07 % of the finest feasible cell of the bracket.
constexpr int kBisections = 10;
/// Weight of the distance to the cell centroid against the plane fit (a tie-breaker).
constexpr double kCentroidWeight = 1e-3;

// The mesh with each vertex shared by several parts split into one copy per part, so every
// vertex belongs to one part; `source` gets the input vertex of each output vertex. Unused
// vertices are left out.
TriangleMesh SplitAtParts(const TriangleMesh& mesh, std::vector<std::int32_t>* source) {
  TriangleMesh out;
  out.parts = mesh.parts;
  out.triangle_part = mesh.triangle_part;
  out.triangles.resize(mesh.num_triangles());
  std::unordered_map<std::uint64_t, std::int32_t> copy;  // (vertex, part) -> output vertex
  copy.reserve(mesh.num_vertices());
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const auto part = static_cast<std::uint32_t>(mesh.triangle_part[t]);
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::uint32_t>(mesh.triangles[t][k]);
      const auto [it, fresh] = copy.emplace((std::uint64_t{v} << 32) | part,
                                            static_cast<std::int32_t>(out.vertices.size()));
      if (fresh) {
        out.vertices.push_back(mesh.vertices[v]);
        source->push_back(static_cast<std::int32_t>(v));
      }
      out.triangles[t][k] = it->second;
    }
  }
  return out;
}

// The part of each vertex (of the first triangle using it: after SplitAtParts, the only one).
std::vector<std::int32_t> VertexParts(const TriangleMesh& mesh) {
  std::vector<std::int32_t> part(mesh.num_vertices(), -1);
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    for (int k = 0; k < 3; ++k) {
      std::int32_t& p = part[static_cast<std::size_t>(mesh.triangles[t][k])];
      if (p < 0) p = mesh.triangle_part[t];
    }
  }
  return part;
}

// Cluster ids of 64-bit cell keys in order of first appearance: an open-addressing table
// (linear probing, at most half full) in place of std::unordered_map, whose node per key made
// it most of the search's time.
class CellIds {
 public:
  explicit CellIds(std::size_t max_keys) {
    std::size_t size = 16;
    while (size < 2 * max_keys) size *= 2;
    keys_.assign(size, 0);
    ids_.assign(size, -1);
    mask_ = size - 1;
  }
  // The id of `key`, the next one (count, then counted) when it is new.
  std::int32_t IdOf(std::uint64_t key, std::int32_t* count) {
    std::size_t slot = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 20U) & mask_;
    while (ids_[slot] >= 0) {
      if (keys_[slot] == key) return ids_[slot];
      slot = (slot + 1) & mask_;
    }
    keys_[slot] = key;
    ids_[slot] = (*count)++;
    return ids_[slot];
  }

 private:
  std::vector<std::uint64_t> keys_;
  std::vector<std::int32_t> ids_;
  std::size_t mask_ = 0;
};

struct Clusters {
  std::vector<std::int32_t> of_vertex;  ///< cluster id per vertex, -1 when unused
  std::int32_t count = 0;
};

class Clusterer {
 public:
  explicit Clusterer(const TriangleMesh& mesh)
      : mesh_(mesh), parts_(VertexParts(mesh)), bounds_(mesh.Bounds()) {}

  // Cells of edge h (from the bounds' minimum corner), one cluster per occupied cell and part.
  Clusters Cluster(double h) const {
    const Eigen::Array3d extent = bounds_.sizes().array();
    const Eigen::Array3d dims = (extent / h).floor() + 1.0;
    const double nparts = static_cast<double>(std::max<std::size_t>(mesh_.parts.size(), 1));
    const bool packable = dims.prod() * nparts < 9e18;  // the key below fits 64 bits
    Clusters out;
    out.of_vertex.assign(mesh_.num_vertices(), -1);
    CellIds ids(mesh_.num_vertices());
    for (std::size_t v = 0; v < mesh_.num_vertices(); ++v) {
      if (parts_[v] < 0) continue;
      const Eigen::Array3d cell =
          ((mesh_.vertices[v] - bounds_.min()).array() / h).floor().min(dims - 1.0).max(0.0);
      const double key = ((cell.x() * dims.y() + cell.y()) * dims.z() + cell.z()) * nparts;
      const std::uint64_t packed =
          packable ? static_cast<std::uint64_t>(key) + static_cast<std::uint64_t>(parts_[v])
                   : static_cast<std::uint64_t>(v);  // too fine to key: never fits a budget
      out.of_vertex[v] = ids.IdOf(packed, &out.count);
    }
    return out;
  }

  // Triangles whose corners fall in three different clusters.
  std::size_t Surviving(const Clusters& c) const {
    std::size_t n = 0;
    for (const Eigen::Vector3i& t : mesh_.triangles) {
      const auto a = c.of_vertex[static_cast<std::size_t>(t[0])];
      const auto b = c.of_vertex[static_cast<std::size_t>(t[1])];
      const auto d = c.of_vertex[static_cast<std::size_t>(t[2])];
      n += (a != b && b != d && a != d) ? 1 : 0;
    }
    return n;
  }

  // The finest cell edge (within the bisection's resolution) whose clustering keeps at
  // most `budget` triangles.
  double Search(std::size_t budget) const {
    const double extent = std::max(bounds_.sizes().maxCoeff(), 1e-9);
    const auto fits = [&](double h) { return Surviving(Cluster(h)) <= budget; };
    double hi =
        std::max(std::sqrt(2.0 * mesh_.SurfaceArea() / static_cast<double>(budget)), extent * 1e-6);
    while (!fits(hi)) hi *= 2.0;  // ends: at h > extent every part is one cluster
    double lo = hi;
    for (int i = 0; i < 40 && fits(lo); ++i) lo *= 0.5;
    if (fits(lo)) return lo;
    for (int i = 0; i < kBisections; ++i) {
      const double mid = std::sqrt(lo * hi);
      (fits(mid) ? hi : lo) = mid;
    }
    return hi;
  }

 private:
  const TriangleMesh& mesh_;
  std::vector<std::int32_t> parts_;
  Eigen::AlignedBox3d bounds_;
};

// Area-weighted plane quadric (symmetric 4x4) and centroid of each cluster.
struct ClusterFit {
  std::vector<Eigen::Matrix4d> quadric;
  std::vector<Eigen::Vector3d> weighted_sum;  ///< sum of area/3 * vertex
  std::vector<double> weight;                 ///< sum of area/3
};

ClusterFit FitClusters(const TriangleMesh& mesh, const Clusters& c) {
  const auto n = static_cast<std::size_t>(c.count);
  ClusterFit fit{std::vector<Eigen::Matrix4d>(n, Eigen::Matrix4d::Zero()),
                 std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Zero()),
                 std::vector<double>(n, 0.0)};
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d cross =
        (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
    const double area = 0.5 * cross.norm();
    if (!(area > 0.0)) continue;
    Eigen::Vector4d plane;
    plane << cross / (2.0 * area), -cross.dot(mesh.corner(t, 0)) / (2.0 * area);
    const Eigen::Matrix4d q = area * plane * plane.transpose();
    std::array<std::int32_t, 3> seen = {-1, -1, -1};
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(mesh.triangles[t][k]);
      const auto id = static_cast<std::size_t>(c.of_vertex[v]);
      fit.weighted_sum[id] += (area / 3.0) * mesh.vertices[v];
      fit.weight[id] += area / 3.0;
      if (std::find(seen.begin(), seen.end(), c.of_vertex[v]) != seen.end()) continue;
      seen[static_cast<std::size_t>(k)] = c.of_vertex[v];
      fit.quadric[id] += q;
    }
  }
  return fit;
}

// Per cluster, the member vertex of least cost (plane fit, then centroid, then index).
std::vector<std::int32_t> Representatives(const TriangleMesh& mesh, const Clusters& c) {
  const ClusterFit fit = FitClusters(mesh, c);
  std::vector<std::int32_t> rep(static_cast<std::size_t>(c.count), -1);
  std::vector<double> best(static_cast<std::size_t>(c.count), 0.0);
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    if (c.of_vertex[v] < 0) continue;
    const auto id = static_cast<std::size_t>(c.of_vertex[v]);
    const Eigen::Vector4d p = mesh.vertices[v].homogeneous();
    const Eigen::Vector3d centroid = fit.weight[id] > 0
                                         ? Eigen::Vector3d(fit.weighted_sum[id] / fit.weight[id])
                                         : mesh.vertices[v];
    const double cost =
        p.dot(fit.quadric[id] * p) +
        kCentroidWeight * fit.weight[id] * (mesh.vertices[v] - centroid).squaredNorm();
    if (rep[id] < 0 || cost < best[id]) {
      rep[id] = static_cast<std::int32_t>(v);
      best[id] = cost;
    }
  }
  return rep;
}

struct TripleHash {
  std::size_t operator()(const std::array<std::int32_t, 3>& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (const std::int32_t x : k) h = (h ^ static_cast<std::uint32_t>(x)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

// Whether triangle t, moved onto the representatives of its clusters `ids`, faces against
// its original orientation (a fold, which would show dark in shading) or degenerates.
bool TurnsOver(const TriangleMesh& mesh, std::size_t t, const std::array<std::int32_t, 3>& ids,
               const std::vector<std::int32_t>& rep) {
  const auto at = [&](int k) -> const Eigen::Vector3d& {
    return mesh.vertices[static_cast<std::size_t>(rep[static_cast<std::size_t>(ids[k])])];
  };
  const Eigen::Vector3d moved = (at(1) - at(0)).cross(at(2) - at(0));
  const Eigen::Vector3d original =
      (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
  return !(moved.dot(original) > 0.0);
}

// The surviving triangles on the representatives (folds and duplicates dropped), vertices
// renumbered.
DecimationResult Collapse(const TriangleMesh& mesh, const Clusters& c) {
  const std::vector<std::int32_t> rep = Representatives(mesh, c);
  DecimationResult out;
  out.mesh.parts = mesh.parts;
  std::vector<std::int32_t> index(static_cast<std::size_t>(c.count), -1);
  std::unordered_set<std::array<std::int32_t, 3>, TripleHash> kept;
  for (std::size_t t = 0; t < mesh.num_triangles(); ++t) {
    std::array<std::int32_t, 3> ids{};
    for (int k = 0; k < 3; ++k)
      ids[k] = c.of_vertex[static_cast<std::size_t>(mesh.triangles[t][k])];
    std::array<std::int32_t, 3> sorted = ids;
    std::sort(sorted.begin(), sorted.end());
    if (sorted[0] == sorted[1] || sorted[1] == sorted[2] || TurnsOver(mesh, t, ids, rep) ||
        !kept.insert(sorted).second) {
      continue;
    }
    Eigen::Vector3i tri;
    for (int k = 0; k < 3; ++k) {
      std::int32_t& i = index[static_cast<std::size_t>(ids[k])];
      if (i < 0) {
        i = static_cast<std::int32_t>(out.mesh.vertices.size());
        const std::int32_t source = rep[static_cast<std::size_t>(ids[k])];
        out.mesh.vertices.push_back(mesh.vertices[static_cast<std::size_t>(source)]);
        out.source_vertex.push_back(source);
      }
      tri[k] = i;
    }
    out.mesh.triangles.push_back(tri);
    out.mesh.triangle_part.push_back(mesh.triangle_part[t]);
  }
  out.mesh.ComputeFaceNormals();
  return out;
}

}  // namespace

DecimationResult DecimateForDisplay(const TriangleMesh& mesh, const DecimationRequest& request) {
  if (request.max_triangles < 1) {
    throw std::invalid_argument("max_triangles: must be at least 1");
  }
  if (const std::string error = mesh.ConsistencyError(); !error.empty()) {
    throw std::invalid_argument("mesh: " + error);
  }
  if (mesh.num_triangles() <= request.max_triangles) {
    DecimationResult out{mesh, std::vector<std::int32_t>(mesh.num_vertices()), 0.0, 0.0};
    std::iota(out.source_vertex.begin(), out.source_vertex.end(), 0);
    return out;
  }
  std::vector<std::int32_t> split_source;
  const TriangleMesh split = SplitAtParts(mesh, &split_source);
  const Clusterer clusterer(split);
  const double h = clusterer.Search(request.max_triangles);
  DecimationResult out = Collapse(split, clusterer.Cluster(h));
  for (std::int32_t& v : out.source_vertex) v = split_source[static_cast<std::size_t>(v)];
  out.cell_mm = h;
  out.error_bound_mm = std::sqrt(3.0) * h;
  return out;
}

std::vector<float> ValuesAtKeptVertices(const DecimationResult& result,
                                        const std::vector<float>& per_input_vertex) {
  std::vector<float> out;
  out.reserve(result.source_vertex.size());
  for (const std::int32_t v : result.source_vertex) {
    if (v < 0 || static_cast<std::size_t>(v) >= per_input_vertex.size()) {
      throw std::invalid_argument("per_input_vertex: " + std::to_string(per_input_vertex.size()) +
                                  " values, but the decimation kept input vertex " +
                                  std::to_string(v) + "; give one value per input vertex");
    }
    out.push_back(per_input_vertex[static_cast<std::size_t>(v)]);
  }
  return out;
}

namespace {

constexpr std::uint32_t kDecimationEncoding = 1;

// The fixed part of an encoding: version, vertex and triangle counts, cell and bound.
struct DecimationHeader {
  std::uint32_t version = kDecimationEncoding;
  std::uint32_t zero = 0;
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  double cell_mm = 0.0;
  double error_bound_mm = 0.0;
};
static_assert(sizeof(DecimationHeader) == 40, "no padding in the header");
static_assert(sizeof(Eigen::Vector3i) == 12, "triangles are copied as arrays of 3 ints");

template <typename T>
void Append(std::string* out, const T* data, std::size_t count) {
  out->append(reinterpret_cast<const char*>(data), count * sizeof(T));
}

}  // namespace

std::uint64_t DecimationKey(const TriangleMesh& mesh, const DecimationRequest& request) {
  Hasher64 h;
  h.AddString("occlude display decimation");
  h.AddValue(kDecimationEncoding);
  h.AddString(kDecimationCodeHash);
  h.AddValue(static_cast<std::uint64_t>(request.max_triangles));
  h.AddValue(MeshContentHash(mesh));
  return h.Finish();
}

std::string EncodeDecimation(const DecimationResult& result) {
  DecimationHeader header;
  header.vertices = result.source_vertex.size();
  header.triangles = result.mesh.num_triangles();
  header.cell_mm = result.cell_mm;
  header.error_bound_mm = result.error_bound_mm;
  std::string out;
  out.reserve(sizeof header + 4 * header.vertices + 16 * header.triangles);
  Append(&out, &header, 1);
  Append(&out, result.source_vertex.data(), result.source_vertex.size());
  Append(&out, result.mesh.triangles.data(), result.mesh.triangles.size());
  Append(&out, result.mesh.triangle_part.data(), result.mesh.triangle_part.size());
  return out;
}

DecimationResult DecodeDecimation(std::string_view bytes, const TriangleMesh& mesh) {
  DecimationHeader header;
  if (bytes.size() < sizeof header) throw std::runtime_error("decimation: shorter than its header");
  std::memcpy(&header, bytes.data(), sizeof header);
  if (header.version != kDecimationEncoding)
    throw std::runtime_error("decimation: encoding " + std::to_string(header.version));
  if (header.vertices > bytes.size() || header.triangles > bytes.size() ||
      bytes.size() != sizeof header + 4 * header.vertices + 16 * header.triangles) {
    throw std::runtime_error("decimation: " + std::to_string(bytes.size()) +
                             " bytes do not hold the counts of its header");
  }
  DecimationResult out;
  out.cell_mm = header.cell_mm;
  out.error_bound_mm = header.error_bound_mm;
  const char* at = bytes.data() + sizeof header;
  out.source_vertex.resize(header.vertices);
  // (No memcpy into an empty vector: its data() may be null.)
  if (header.vertices > 0) std::memcpy(out.source_vertex.data(), at, 4 * header.vertices);
  at += 4 * header.vertices;
  out.mesh.triangles.resize(header.triangles);
  if (header.triangles > 0)  // the bytes of Vector3i are its three ints
    std::memcpy(static_cast<void*>(out.mesh.triangles.data()), at, 12 * header.triangles);
  at += 12 * header.triangles;
  out.mesh.triangle_part.resize(header.triangles);
  if (header.triangles > 0) std::memcpy(out.mesh.triangle_part.data(), at, 4 * header.triangles);
  out.mesh.vertices.reserve(header.vertices);
  for (const std::int32_t v : out.source_vertex) {
    if (v < 0 || static_cast<std::size_t>(v) >= mesh.num_vertices())
      throw std::runtime_error("decimation: a kept vertex is not one of the mesh's");
    out.mesh.vertices.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
  }
  out.mesh.parts = mesh.parts;
  // Indices and parts checked before the normals read the corners.
  out.mesh.face_normals.assign(header.triangles, Eigen::Vector3d::Zero());
  if (const std::string error = out.mesh.ConsistencyError(); !error.empty())
    throw std::runtime_error("decimation: " + error);
  out.mesh.ComputeFaceNormals();
  return out;
}

}  // namespace occlude::io
