// Internal pieces of the synthetic jaw generator (see occlude/io/synthetic_jaws.h for the
// contract). Data flow: tooth layout (synthetic_layout.cpp) + arch curve (synthetic_arch.cpp)
// -> crown height functions (synthetic_crowns.cpp) sampled on one (s, t) grid shared by both
// jaws (synthetic_grid.cpp) -> gap function and contacts (synthetic_gap.cpp, with the Class II
// alternative's record from synthetic_alternative.cpp) -> closed slab meshes
// (synthetic_slab.cpp) -> invariant checks (synthetic_verify.cpp) -> landmarks on the final
// surfaces and the relationships they make (synthetic_landmarks.cpp,
// synthetic_relationships.cpp), all driven by MakeSyntheticJawPair (synthetic_jaws.cpp).
//
// Parameter domain: s is arc length along the arch curve (mm, 0 on the midline, s > 0 towards
// the patient's left = +x), t the signed distance across it (mm, t > 0 buccal/labial). A point
// (s, t) lies at C(s) + t N(s) in the xz-plane of L; heights are y in L.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "occlude/io/dental.h"
#include "occlude/io/synthetic_jaws.h"
#include "occlude/io/triangle_mesh.h"

namespace occlude::io::synthetic {

// ---------------------------------------------------------------- arch (synthetic_arch.cpp)

/// The dental arch curve C(s) in the xz-plane of L. Its tangent makes the angle theta(s) with +x,
/// turning towards -z (posterior): theta = pi/2 F(|s| / bend_length) sign(s) over the bend and
/// exactly pi/2 beyond, so the posterior segments are straight and parallel to the anterior
/// axis z (a shift of the upper along z slides them along themselves: the Class II
/// alternative, synthetic_alternative.cpp). F blends a uniform turn (round incisor front, share
/// round_share) with one peaking at mid-bend, where the canines stand (the arch's corners).
struct ArchCurve {
  double bend_length = 36.0;  ///< mm of arc from the midline to the straight posterior segments
  double round_share = 0.25;  ///< share of the turn spread over the bend evenly
  double z_offset = 0.0;      ///< mm, added to z so that the dentition is centred on z = 0
};

/// Tangent angle theta(s), rad.
double ArchAngle(const ArchCurve& arch, double s);
/// C(s) as (x, z) in L, mm.
Eigen::Vector2d ArchPoint(const ArchCurve& arch, double s);
/// Unit tangent T(s) as (x, z) in L, towards growing s.
Eigen::Vector2d ArchTangent(const ArchCurve& arch, double s);
/// Outward (buccal/labial) unit normal N(s) as (x, z) in L.
Eigen::Vector2d ArchNormal(const ArchCurve& arch, double s);
/// Curvature of C at s, 1/mm (>= 0: N points away from the centre of curvature).
double ArchCurvature(const ArchCurve& arch, double s);
/// The largest curvature of the arch, 1/mm.
double MaxArchCurvature(const ArchCurve& arch);

// ------------------------------------------------------------ layout (synthetic_layout.cpp)

enum ToothClass : int {
  kCentralIncisor = 0,
  kLateralIncisor,
  kCanine,
  kFirstPremolar,
  kSecondPremolar,
  kFirstMolar,
  kSecondMolar,
  kNumToothClasses
};

/// One cusp: a Gaussian bump amplitude exp(-d^2 / (2 sigma^2)) of the occlusal relief, d the
/// distance from its tip (s, t) in the parameter domain.
struct Cusp {
  double s = 0.0, t = 0.0;                     ///< tip position in the parameter domain, mm
  double amplitude = 0.0;                      ///< mm
  double sigma = 1.0;                          ///< mm
  LandmarkType type = LandmarkType::kCuspTip;  ///< which cusp of clinical.md it is
};

/// One crown. Its height above (lower) or below (upper) the jaw's gingiva level is a product of
/// two 1-D shoulder profiles (footprint |u| < 1, |v| < 1 with u, v the normalised offsets from
/// the centre) times crown_height plus an occlusal relief <= 0 (cusps, fossae, incisal edge).
struct Tooth {
  int number = 0;  ///< Universal number
  ToothClass tooth_class = kCentralIncisor;
  int side = 1;               ///< +1 the patient's left (s > 0), -1 the right
  double s_mesial = 0.0;      ///< mm, where the crown meets its mesial neighbour (contact point)
  double s_distal = 0.0;      ///< mm, where it meets its distal neighbour (or would)
  double s_center = 0.0;      ///< mm
  double half_length = 0.0;   ///< mm along s, including the proximal overlap with neighbours
  double t_center = 0.0;      ///< mm
  double half_width = 0.0;    ///< mm along t
  double crown_height = 0.0;  ///< mm from the gingiva level to the cusp tips / incisal edge
  double relief_cap = 0.0;    ///< posterior/canine: cusp bumps are clamped to [floor, cap], mm
  double relief_floor = 0.0;  ///< (the relief is clamp(max bump) - cap <= 0)
  double edge_v = 0.0;        ///< incisors: normalised position v of the incisal edge
  double edge_lingual = 0.0;  ///< incisors: relief = -k (v - edge_v)^2, k lingual / buccal, mm
  double edge_buccal = 0.0;
  std::vector<Cusp> cusps;
};

/// The teeth of one jaw, sorted by s_center, and its gingiva level.
struct JawLayout {
  std::vector<Tooth> teeth;
  double gingiva_y = 0.0;  ///< y in L of the gingiva around the crowns, mm
};

/// Both jaws at the bite, in L, and the slab's parameter domain.
struct DentitionLayout {
  JawLayout lower;
  JawLayout upper;
  double s_min = 0.0, s_max = 0.0;  ///< mm, the slab's extent along the arch
  double t_min = 0.0, t_max = 0.0;  ///< mm, across (lingual < 0 < buccal)
  double lower_base_y = 0.0;        ///< y of the lower slab's flat back, mm
  double upper_top_y = 0.0;         ///< y of the upper slab's flat back, mm
  double upper_origin_y = 0.0;      ///< y in L of U's origin (upper posterior cusp level), mm
  ArchCurve arch;
};

DentitionLayout MakeDentitionLayout(std::uint32_t seed);

// ------------------------------------------------------------ crowns (synthetic_crowns.cpp)

/// Largest crown height of a jaw at (s, t) (>= 0, mm) and the index in JawLayout::teeth of the
/// crown that reaches it (-1: no crown there, i.e. gingiva).
struct CrownSample {
  double height = 0.0;
  int tooth = -1;
};
CrownSample SampleCrowns(const JawLayout& jaw, double s, double t);

// ---------------------------------------------------------------- grid (synthetic_grid.cpp)

/// The (s, t) grid shared by both occlusal surfaces: (ns + 1) x (nt + 1) vertices, uniform in s
/// and t. Sharing it (same vertices in xz, same diagonals) makes the upper-minus-lower height
/// difference on every triangle the linear interpolant of its vertex values: the key to the
/// exact no-penetration guarantee.
struct OcclusalGrid {
  int ns = 0, nt = 0;
  double s0 = 0.0, ds = 0.0, t0 = 0.0, dt = 0.0;  ///< mm
  double max_curvature = 0.0;                     ///< of the arch curve, 1/mm
  std::vector<Eigen::Vector2d> xz;                ///< vertex (x, z) in L, mm
  int Index(int i, int j) const { return i * (nt + 1) + j; }
  double S(int i) const { return s0 + ds * i; }
  double T(int j) const { return t0 + dt * j; }
  std::size_t num_vertices() const { return xz.size(); }
};

/// Calls visit(v, d) for the grid vertices v whose xz distance d to `centre` (the point at grid
/// parameters (s, t)) is at most `radius` (a few mm at most).
template <typename Visit>
void ForGridVerticesNear(const OcclusalGrid& grid, const Eigen::Vector2d& centre, double s,
                         double t, double radius, Visit visit) {
  // Along s the spacing at t is ds (1 + t kappa) >= ds (1 + min(t, 0) kappa_max), > 0 because
  // the grid does not fold (CheckInvariants); the extra cell covers the bending of the rows.
  const double stretch = 1.0 + std::min(t - radius, 0.0) * grid.max_curvature;
  const int di = static_cast<int>(std::ceil(radius / (grid.ds * stretch))) + 1;
  const int dj = static_cast<int>(std::ceil(radius / grid.dt)) + 1;
  const auto ic = static_cast<int>(std::lround((s - grid.s0) / grid.ds));
  const auto jc = static_cast<int>(std::lround((t - grid.t0) / grid.dt));
  for (int i = std::max(0, ic - di); i <= std::min(grid.ns, ic + di); ++i) {
    for (int j = std::max(0, jc - dj); j <= std::min(grid.nt, jc + dj); ++j) {
      const int v = grid.Index(i, j);
      const double d = (grid.xz[static_cast<std::size_t>(v)] - centre).norm();
      if (d <= radius) visit(v, d);
    }
  }
}

/// Longest cell diagonal in xz, mm: cells are ds (1 + t kappa) long along s, longest at t_max.
inline double CellDiagonal(const OcclusalGrid& grid) {
  const double stretch = 1.0 + std::max(grid.T(grid.nt), 0.0) * grid.max_curvature;
  return std::hypot(grid.ds * stretch, grid.dt);
}

/// Triangles of a closed slab over an ns x nt grid (occlusal side, walls, back).
std::size_t SlabTriangleCount(int ns, int nt);
/// The grid whose slab has as close to `triangle_budget` triangles as the layout allows.
OcclusalGrid MakeOcclusalGrid(const DentitionLayout& layout, std::size_t triangle_budget);

/// Per-vertex samples of both jaws' designs on the grid, L frame, mm.
struct OcclusalFields {
  std::vector<double> lower_y;         ///< H_L: the lower occlusal surface
  std::vector<double> upper_design_y;  ///< H_U0: the upper crowns as designed (may dip into H_L)
  std::vector<int> lower_tooth;        ///< crown index per vertex, -1 = gingiva
  std::vector<int> upper_tooth;
};
OcclusalFields SampleFields(const DentitionLayout& layout, const OcclusalGrid& grid);

/// The occlusal triangles (vertex indices into the grid), oriented with normal +y (lower jaw
/// convention). Each grid cell is split along the diagonal whose ends differ least in
/// `lower_y`; both jaws use this one triangulation.
std::vector<Eigen::Vector3i> OcclusalTriangles(const OcclusalGrid& grid,
                                               const std::vector<double>& lower_y);

// ------------------------------------------------------ clearance (synthetic_clearance.cpp)

/// The separation the bite is built for: pulling the jaws kPullApart apart along the occlusal
/// axis leaves them at least kKeptApart apart everywhere (the tests accept 0.36 mm), so they
/// are tight only at the contacts. Both mm.
inline constexpr double kPullApart = 0.5;
inline constexpr double kKeptApart = 0.38;

/// Vertical gap a triangle of the surface with heights y needs: over a slope alpha a vertical
/// gap g is a normal gap g cos(alpha), so (kKeptApart + margin) / cos(alpha) - kPullApart,
/// >= 0, mm.
double TriangleClearance(const OcclusalGrid& grid, const std::vector<double>& y,
                         const Eigen::Vector3i& tri);
/// Per vertex: the largest TriangleClearance of the lower triangles around it.
std::vector<double> SlopeClearance(const OcclusalGrid& grid, const std::vector<double>& lower_y,
                                   const std::vector<Eigen::Vector3i>& triangles);
/// Per vertex v: max over the vertices z within r = kKeptApart + margin of v (xz distance h)
/// of H_L(z) - H_L(v) + sqrt(r^2 - h^2) - kPullApart, >= 0: the gap at v that keeps an upper
/// point over v (or a lower point at z) apart from the other jaw after the pull where the
/// lower surface rises beside v (concave corners of the relief). Left 0 where it cannot exceed
/// `known_gap` (a gap the vertex gets anyway).
std::vector<double> RiseClearance(const OcclusalGrid& grid, const std::vector<double>& lower_y,
                                  const std::vector<double>& known_gap);
/// Exact distance from p (a point over grid vertex v) to the occlusal triangles with heights y,
/// capped at `radius` (mm).
double DistanceToSurfaceNear(const OcclusalGrid& grid, const std::vector<double>& y,
                             const std::vector<Eigen::Vector3i>& triangles, int v,
                             const Eigen::Vector3d& p, double radius);

// -------------------------------------------------- alternative (synthetic_alternative.cpp)

/// The full-cusp Class II alternative the bite is built to have: the upper jaw moved by this
/// along +z in L (anterior: upper mesial by about a premolar width), mm.
inline constexpr double kClass2ShiftMm = 7.0;

/// Per grid vertex, the lift E >= 0 of the upper surface over the lower one (H_U >= H_L + E)
/// that keeps the upper, moved by kClass2ShiftMm along +z, above the lower occlusal surface at
/// the vertices of both (see synthetic_alternative.cpp). Zero where nothing is needed.
std::vector<double> AlternativeLift(const OcclusalGrid& grid, const std::vector<double>& lower_y,
                                    const std::vector<Eigen::Vector3i>& triangles);
/// The lift thinned so that the alternative touches at spots rather than wherever the lift
/// binds: spots kAlternativeSpotSpacingMm apart among the vertices where `lift` exceeds the
/// upper's other gaps `others` (there the moved upper rests on the lower), and beyond them the
/// lift raised by the contact proximity C of the spots (capped at 4 lift, so it stays
/// continuous and 0 where `lift` is). Returns E >= lift, equal to it where lift == 0.
std::vector<double> ThinAlternativeLift(const OcclusalGrid& grid, const std::vector<double>& lift,
                                        const std::vector<double>& others);

// ------------------------------------------------------------------ gap (synthetic_gap.cpp)

/// The upper occlusal surface H_U = H_L + G and the contacts.
struct GapResult {
  std::vector<double> upper_y;      ///< H_U per grid vertex, L frame, mm
  std::vector<int> contact_vertex;  ///< grid vertices where G == 0 exactly (sorted)
};
/// C per vertex for a set of contact vertices: 0 within kPatchRadius of one, rising as
/// z (2 - z) with z = (distance - kPatchRadius) / kGapRamp to kFarGap (synthetic_gap.cpp), mm.
std::vector<double> ContactProximity(const OcclusalGrid& grid, const std::vector<int>& contacts);

GapResult MakeUpperSurface(const DentitionLayout& layout, const OcclusalGrid& grid,
                           const OcclusalFields& fields,
                           const std::vector<Eigen::Vector3i>& triangles);

// -------------------------------------------------------- landmarks (synthetic_landmarks.cpp)

/// The clinical landmarks of every tooth of `jaw` (its occlusal heights `occlusal_y` over the
/// grid and crown index per vertex `vertex_tooth`), in L, on the mesh; sorted by FDI number,
/// each tooth's in a fixed type order.
std::vector<Landmark> JawLandmarks(const JawLayout& jaw, bool upper, const ArchCurve& arch,
                                   const OcclusalGrid& grid,
                                   const std::vector<Eigen::Vector3i>& triangles,
                                   const std::vector<double>& occlusal_y,
                                   const std::vector<int>& vertex_tooth);

// ------------------------------------------------ relationships (synthetic_relationships.cpp)

/// clinical.md's relationships from the landmarks of both jaws in L at the bite.
SyntheticRelationships DesignedRelationships(const std::vector<Landmark>& lower_L,
                                             const std::vector<Landmark>& upper_L);

// ---------------------------------------------------------------- slab (synthetic_slab.cpp)

/// A closed slab: the occlusal height field `occlusal_y` over the grid, vertical walls along
/// the grid boundary and a flat back at `back_y`. `occlusal_faces_up`: true for the lower jaw
/// (solid below the occlusal surface), false for the upper. Occlusal triangles get the part
/// of the majority of their vertices (`vertex_part`), walls and back part 0.
TriangleMesh MakeSlab(const OcclusalGrid& grid, const std::vector<Eigen::Vector3i>& triangles,
                      const std::vector<double>& occlusal_y, double back_y, bool occlusal_faces_up,
                      const std::vector<std::int32_t>& vertex_part, std::vector<MeshPart> parts);

// ------------------------------------------------------------ verify (synthetic_verify.cpp)

/// Cheap O(n) checks of the generator's invariants on the two slabs in L; returns an empty
/// string when they hold, else what is violated.
std::string CheckInvariants(const OcclusalGrid& grid, const OcclusalFields& fields,
                            const GapResult& gap, const TriangleMesh& lower_L,
                            const TriangleMesh& upper_L, std::size_t triangle_budget);

}  // namespace occlude::io::synthetic
