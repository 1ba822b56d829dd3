// The gap function of the synthetic bite and its contacts. The upper occlusal surface is the
// lower one lifted by a gap G >= 0 at every vertex of the shared grid:
//
//   H_U = H_L + G,   G = max(C, D, E, H_U0 - H_L)   (G = 0 at the contact vertices)
//
//   H_U0  the upper crowns as designed. Where they would dip into the lower jaw (or come
//         closer than C, D or E) the upper surface takes the lower's shape lifted by C, D or
//         E, like a bite record: upper cusps seat in the lower fossae.
//   C     contact proximity: exactly 0 within kPatchRadius of a contact vertex, rising to
//         kFarGap within kGapRamp beyond, so the jaws touch only at the contacts.
//   D     clearance (synthetic_clearance.cpp): enough vertical gap that pulling the jaws
//         kPullApart apart opens at least kKeptApart everywhere.
//   E     the Class II alternative's record (synthetic_alternative.cpp): where the upper,
//         moved a premolar width mesially, would dip into the lower. Contacts lie where E = 0.
//
// Contacts: on the four flanks of each cusp, grid vertices on inclines (so that the bite locks
// against slides and rotations) near where the design meets the lower jaw, where both pulls
// (upper point up from the lower surface, lower point down from the upper one) are checked
// exactly to open kKeptApart.
//
// Because both surfaces use the same grid and triangles, H_U - H_L on any triangle is the
// linear interpolant of G >= 0: the piecewise-linear surfaces cannot interpenetrate, and they
// touch (difference exactly 0) at the contact vertices.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

#include "occlude/angles.h"
#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

constexpr double kPatchRadius = 0.25;         // mm, C == 0 within this distance of a contact
constexpr double kGapRamp = 1.5;              // mm, C rises over this distance beyond the patch
constexpr double kFarGap = 0.5;               // mm, C away from contacts
constexpr double kContactSearchRadius = 1.0;  // mm around a flank point to look for a contact
constexpr double kDesignReach = 0.3;  // mm: the upper design may sit this far above a contact
constexpr double kMinFlankSlope =
    RadiansFromDegrees(12.0);  // a contact incline locks at first order
constexpr double kMaxFlankSlope =
    RadiansFromDegrees(36.0);  // and still opens kKeptApart when pulled

Eigen::Vector3d LowerPoint(const OcclusalGrid& grid, const OcclusalFields& fields, int v) {
  const Eigen::Vector2d& xz = grid.xz[static_cast<std::size_t>(v)];
  return Eigen::Vector3d(xz.x(), fields.lower_y[static_cast<std::size_t>(v)], xz.y());
}

/// The grid vertex nearest to `centre` (the point at grid parameters (s, t)) within
/// kContactSearchRadius that satisfies `eligible`, or -1.
template <typename Eligible>
int NearestEligible(const OcclusalGrid& grid, const Eigen::Vector2d& centre, double s, double t,
                    Eligible eligible) {
  std::vector<std::pair<double, int>> near;  // (distance, vertex)
  ForGridVerticesNear(grid, centre, s, t, kContactSearchRadius,
                      [&](int v, double d) { near.emplace_back(d, v); });
  std::sort(near.begin(), near.end());
  for (const std::pair<double, int>& candidate : near) {
    if (eligible(candidate.second)) return candidate.second;
  }
  return -1;
}

/// Slope angle (rad) of the lower occlusal surface at grid vertex v, from its grid neighbours
/// (central differences; one-sided at the border).
double LowerSlope(const OcclusalGrid& grid, const OcclusalFields& fields, int v) {
  const int i = v / (grid.nt + 1), j = v % (grid.nt + 1);
  const int i0 = std::max(0, i - 1), i1 = std::min(grid.ns, i + 1);
  const int j0 = std::max(0, j - 1), j1 = std::min(grid.nt, j + 1);
  const Eigen::Vector3d ts =
      LowerPoint(grid, fields, grid.Index(i1, j)) - LowerPoint(grid, fields, grid.Index(i0, j));
  const Eigen::Vector3d tt =
      LowerPoint(grid, fields, grid.Index(i, j1)) - LowerPoint(grid, fields, grid.Index(i, j0));
  const Eigen::Vector3d n = ts.cross(tt);
  if (n.norm() == 0.0) return 0.0;
  return std::acos(std::min(1.0, std::abs(n.normalized().y())));
}

/// Flank contacts: for each cusp of either jaw (canines and posteriors), one contact on each
/// of its four flanks (mesial, distal, buccal, lingual: one cusp sigma from the tip in the
/// parameter domain), at the nearest grid vertex within kContactSearchRadius where both jaws
/// have a crown, the upper design comes within kDesignReach of the lower surface (or dips into
/// it), the lower surface slopes between kMinFlankSlope and kMaxFlankSlope, and a point
/// kPullApart above the lower surface is kKeptApart from it. Contacts on inclines facing all
/// horizontal directions lock the bite: any slide or rotation of the upper jaw drives some
/// contact into the lower one at first order, so the jaws must open and every other contact
/// opens with them (cusp tips and fossa bottoms are flat and would let the jaws slide).
std::vector<int> SelectContacts(const DentitionLayout& layout, const OcclusalGrid& grid,
                                const OcclusalFields& fields,
                                const std::vector<Eigen::Vector3i>& triangles,
                                const std::vector<double>& lift) {
  const auto eligible = [&](int v) {
    const auto k = static_cast<std::size_t>(v);
    if (fields.lower_tooth[k] < 0 || fields.upper_tooth[k] < 0) return false;
    if (lift[k] > 0.0) return false;
    if (fields.upper_design_y[k] > fields.lower_y[k] + kDesignReach) return false;
    const double slope = LowerSlope(grid, fields, v);
    if (slope < kMinFlankSlope || slope > kMaxFlankSlope) return false;
    const Eigen::Vector3d pulled =
        LowerPoint(grid, fields, v) + kPullApart * Eigen::Vector3d::UnitY();
    return DistanceToSurfaceNear(grid, fields.lower_y, triangles, v, pulled, kKeptApart) >=
           kKeptApart;
  };
  static constexpr double kFlank[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  std::vector<int> contacts;
  for (const JawLayout* jaw : {&layout.lower, &layout.upper}) {
    for (const Tooth& tooth : jaw->teeth) {
      for (const Cusp& cusp : tooth.cusps) {
        for (const auto& f : kFlank) {
          const double s = cusp.s + f[0] * cusp.sigma, t = cusp.t + f[1] * cusp.sigma;
          const Eigen::Vector2d at = ArchPoint(layout.arch, s) + t * ArchNormal(layout.arch, s);
          const int v = NearestEligible(grid, at, s, t, eligible);
          if (v >= 0) contacts.push_back(v);
        }
      }
    }
  }
  std::sort(contacts.begin(), contacts.end());
  contacts.erase(std::unique(contacts.begin(), contacts.end()), contacts.end());
  return contacts;
}

/// H_U = H_L + max(C, D, E, H_U0 - H_L), and exactly H_L at the contact vertices (where C = 0,
/// E = 0 and H_U0 <= H_L; the clearance there is checked exactly instead).
std::vector<double> UpperHeights(const OcclusalFields& fields, const std::vector<double>& proximity,
                                 const std::vector<double>& clearance,
                                 const std::vector<double>& lift,
                                 const std::vector<int>& contacts) {
  std::vector<double> upper_y(fields.lower_y.size());
  for (std::size_t v = 0; v < upper_y.size(); ++v) {
    const double design_gap = fields.upper_design_y[v] - fields.lower_y[v];
    upper_y[v] = fields.lower_y[v] + std::max({proximity[v], clearance[v], lift[v], design_gap});
  }
  for (const int c : contacts) {
    upper_y[static_cast<std::size_t>(c)] = fields.lower_y[static_cast<std::size_t>(c)];
  }
  return upper_y;
}

/// True when pulling the jaws kPullApart apart leaves the two surfaces over grid vertex v at
/// least kKeptApart from each other: the upper point (moved up) from the lower surface and the
/// lower point (moved down) from the upper surface, both measured exactly.
bool OpensFully(const OcclusalGrid& grid, const OcclusalFields& fields,
                const std::vector<double>& upper_y, const std::vector<Eigen::Vector3i>& triangles,
                int v) {
  const Eigen::Vector3d lower = LowerPoint(grid, fields, v);
  const Eigen::Vector3d upper(lower.x(), upper_y[static_cast<std::size_t>(v)], lower.z());
  const Eigen::Vector3d pull = kPullApart * Eigen::Vector3d::UnitY();
  return DistanceToSurfaceNear(grid, fields.lower_y, triangles, v, upper + pull, kKeptApart) >=
             kKeptApart &&
         DistanceToSurfaceNear(grid, upper_y, triangles, v, lower - pull, kKeptApart) >= kKeptApart;
}

/// The contacts around which pulling the jaws apart does not open kKeptApart: a vertex within
/// reach of the triangles at the contact fails OpensFully (e.g. an upper slope rising from the
/// contact faster than the lower surface beside it).
std::vector<int> TightContacts(const OcclusalGrid& grid, const OcclusalFields& fields,
                               const std::vector<double>& upper_y,
                               const std::vector<Eigen::Vector3i>& triangles,
                               const std::vector<int>& contacts) {
  // The triangles at the contact reach one cell diagonal beyond it.
  const double reach = kKeptApart + CellDiagonal(grid);
  std::vector<int> tight;
  for (const int c : contacts) {
    const int i = c / (grid.nt + 1);
    const int j = c % (grid.nt + 1);
    bool opens = true;
    ForGridVerticesNear(
        grid, grid.xz[static_cast<std::size_t>(c)], grid.S(i), grid.T(j), reach,
        [&](int v, double) { opens = opens && OpensFully(grid, fields, upper_y, triangles, v); });
    if (!opens) tight.push_back(c);
  }
  return tight;
}

/// H_U0 - H_L per vertex.
std::vector<double> DesignGap(const OcclusalFields& fields) {
  std::vector<double> gap(fields.lower_y.size());
  for (std::size_t v = 0; v < gap.size(); ++v)
    gap[v] = fields.upper_design_y[v] - fields.lower_y[v];
  return gap;
}

/// D per vertex: the larger of the slope and rise clearances.
std::vector<double> Clearance(const OcclusalGrid& grid, const OcclusalFields& fields,
                              const std::vector<Eigen::Vector3i>& triangles) {
  std::vector<double> clearance = SlopeClearance(grid, fields.lower_y, triangles);
  const std::vector<double> rise = RiseClearance(grid, fields.lower_y, DesignGap(fields));
  for (std::size_t v = 0; v < clearance.size(); ++v) {
    clearance[v] = std::max(clearance[v], rise[v]);
  }
  return clearance;
}

}  // namespace

GapResult MakeUpperSurface(const DentitionLayout& layout, const OcclusalGrid& grid,
                           const OcclusalFields& fields,
                           const std::vector<Eigen::Vector3i>& triangles) {
  const std::vector<double> lift = AlternativeLift(grid, fields.lower_y, triangles);
  const std::vector<double> clearance = Clearance(grid, fields, triangles);
  GapResult result;
  result.contact_vertex = SelectContacts(layout, grid, fields, triangles, lift);
  std::vector<double> proximity;
  for (;;) {  // each round drops at least one contact, so this ends
    proximity = ContactProximity(grid, result.contact_vertex);
    result.upper_y = UpperHeights(fields, proximity, clearance, lift, result.contact_vertex);
    const std::vector<int> tight =
        TightContacts(grid, fields, result.upper_y, triangles, result.contact_vertex);
    if (tight.empty()) break;
    std::vector<int> kept;
    std::set_difference(result.contact_vertex.begin(), result.contact_vertex.end(), tight.begin(),
                        tight.end(), std::back_inserter(kept));
    result.contact_vertex = std::move(kept);
  }
  // The alternative's contact thinned to spots; the lift only grows where it was > 0, so the
  // contacts, the no-penetration and the pull-apart clearance of the bite are unchanged.
  std::vector<double> others = DesignGap(fields);
  for (std::size_t v = 0; v < others.size(); ++v) {
    others[v] = std::max({others[v], proximity[v], clearance[v]});
  }
  const std::vector<double> thinned = ThinAlternativeLift(grid, lift, others);
  result.upper_y = UpperHeights(fields, proximity, clearance, thinned, result.contact_vertex);
  return result;
}

/// C per vertex: 0 within kPatchRadius of a contact vertex, rising as z (2 - z) with
/// z = (distance - kPatchRadius) / kGapRamp to kFarGap.
std::vector<double> ContactProximity(const OcclusalGrid& grid, const std::vector<int>& contacts) {
  std::vector<double> gap(grid.num_vertices(), kFarGap);
  for (const int c : contacts) {
    const auto k = static_cast<std::size_t>(c);
    const int i = c / (grid.nt + 1);
    const int j = c % (grid.nt + 1);
    ForGridVerticesNear(grid, grid.xz[k], grid.S(i), grid.T(j), kPatchRadius + kGapRamp,
                        [&](int v, double d) {
                          const double z = std::clamp((d - kPatchRadius) / kGapRamp, 0.0, 1.0);
                          double& g = gap[static_cast<std::size_t>(v)];
                          g = std::min(g, kFarGap * z * (2.0 - z));
                        });
  }
  return gap;
}

}  // namespace occlude::io::synthetic
