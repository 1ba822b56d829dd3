// A mesh reduced to a triangle budget for display (the 3D viewer shows both
// jaws at a few hundred thousand triangles at most; a scanned jaw can have more).
//
// Method: vertex clustering on a uniform grid (cell edge h, searched so the
// result meets the budget with the finest cell), within each part separately
// (parts are never merged, so tooth numbers carry over; a vertex several parts
// share becomes one vertex per part, as LoadJawParts gives). Each occupied cell of a
// part is replaced by one of its *original* vertices: the one that best fits the
// planes of the triangles around the cell (least area-weighted squared plane
// distance, ties to the cell's area-weighted centroid, then the lowest index).
// A triangle whose corners fall in three different cells survives, with its
// corner order and part, unless it would turn over (its normal against the
// original's: a fold, dark in shading); duplicates (the same three kept
// vertices) are dropped.
//
// Guarantee: every point of the result lies within `error_bound_mm` = sqrt(3) h
// (the cell diagonal) of the original surface, since each kept corner is an
// original vertex in the same cell as the corner it replaces. The converse
// (original within the bound of the result) holds on smooth surfaces sampled
// finer than h, where every cell keeps a triangle around its vertex; thin
// features narrower than a cell may vanish.
// Deterministic (no randomness, no threads); O(V + T) per candidate cell size.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::io {

struct DecimationRequest {
  /// At most this many triangles in the result (>= 1, else std::invalid_argument naming
  /// "max_triangles"). A mesh already within it is returned unchanged.
  std::size_t max_triangles = 100000;
};

struct DecimationResult {
  /// Same frame and parts as the input; vertices in order of first use, each used by
  /// triangles of one part only.
  TriangleMesh mesh;
  /// Per vertex of `mesh`: the index of the input vertex it is (same coordinates exactly), so
  /// per-vertex values of the input (distances, colours) carry over by lookup.
  std::vector<std::int32_t> source_vertex;
  double cell_mm = 0.0;         ///< the grid's cell edge h; 0 when nothing was reduced
  double error_bound_mm = 0.0;  ///< sqrt(3) h: see the guarantee above
};

/// Reduces `mesh` to at most request.max_triangles triangles. Throws
/// std::invalid_argument naming the field for a bad request or an inconsistent mesh.
DecimationResult DecimateForDisplay(const TriangleMesh& mesh, const DecimationRequest& request);

/// Per vertex of result.mesh, the value its source vertex has in `per_input_vertex` (one
/// value per input vertex, else std::invalid_argument naming "per_input_vertex").
std::vector<float> ValuesAtKeptVertices(const DecimationResult& result,
                                        const std::vector<float>& per_input_vertex);

/// The key of DecimateForDisplay(mesh, request) for a cache: the mesh's content hash, the
/// request, the encoding's version and a hash of the decimation's code (made by the build).
std::uint64_t DecimationKey(const TriangleMesh& mesh, const DecimationRequest& request);

/// `result`, of DecimateForDisplay(mesh, ...), as bytes that give it back exactly with the same
/// `mesh`: the kept vertices' input indices, the triangles and their parts, the cell (the
/// coordinates are the input's vertices, the parts the input's, the normals recomputed).
std::string EncodeDecimation(const DecimationResult& result);
/// The result EncodeDecimation wrote, for `mesh`; throws std::runtime_error when the bytes are
/// malformed or do not fit `mesh` (an index out of range, an inconsistent mesh).
DecimationResult DecodeDecimation(std::string_view bytes, const TriangleMesh& mesh);

}  // namespace occlude::io
