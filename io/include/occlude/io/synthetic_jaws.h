// The procedural synthetic jaw pair: the project's embedded default for the demo, the tests
// and scaling studies. Deterministic (the same options give bit-identical meshes), fast (well
// under 2 s for 500,000 triangles per jaw) and anatomically plausible: a horseshoe arch of 14
// teeth per jaw in Class I interdigitation, with a known bite pose and known contact points.
//
// Frames (millimetres, right-handed), like the real cases in ../shared/data (upper above the
// lower along +y):
//   L  lower jaw frame: x towards the patient's left, y up (occlusal axis, lower -> upper),
//      z anterior (towards the incisors). Origin on the midline, at the level of the lower
//      cusp tips (occlusal plane), half-way along z between the front of the arch and the
//      distal ends of the second molars.
//   U  upper jaw frame: axes parallel to L's at the bite; origin on the midline, at the level
//      of the upper posterior cusp tips (the centre of the upper occlusal surface), which is
//      1.5 mm below L's origin because upper cusps overlap the lower ones vertically (overbite)
//      and seat in their fossae. X_LU is therefore a pure translation (0, -1.5, 0) mm.
// Both meshes are single closed, edge-manifold, outward-oriented, non-self-intersecting
// surfaces (a "horseshoe slab": occlusal height field, vertical side walls, flat back), about
// 70 x 58 mm in xz with gingiva; the lower arch is about 54 mm wide across the middle of the
// first molar crowns (57 mm at their widest) and 48 mm deep.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::io {

/// Smallest and largest accepted SyntheticJawOptions::triangles_per_jaw.
inline constexpr std::size_t kMinSyntheticTriangles = 5000;
inline constexpr std::size_t kMaxSyntheticTriangles = 500000;

/// Contract of the ground truth (mm): at X_LU no point of one jaw lies deeper than this inside
/// the other, and both surfaces pass within this distance of every returned contact point.
/// (By construction both numbers are 0 up to double rounding; see io/src/synthetic_gap.cpp.)
/// Also by construction: opened 0.5 mm along the occlusal axis the jaws are >= 0.38 mm apart,
/// so the bite is tight only at the contacts.
inline constexpr double kSyntheticContactToleranceMm = 0.01;

struct SyntheticJawOptions {
  /// Triangle budget per jaw; each mesh has this many triangles within 10 % (in practice within
  /// 1 %). Valid range kMinSyntheticTriangles..kMaxSyntheticTriangles, else
  /// std::invalid_argument naming "triangles_per_jaw".
  std::size_t triangles_per_jaw = 20000;
  /// Varies tooth sizes (+-3 %), crown heights (+-4 %) and cusp heights (+-10 %) slightly;
  /// every seed gives one deterministic pair.
  std::uint32_t seed = 1;
};

/// A point where the arches touch at the bite X_LU.
struct SyntheticContact {
  Eigen::Vector3d p_L = Eigen::Vector3d::Zero();  ///< contact point in L, mm (a vertex of both)
  int upper_tooth = 0;  ///< Universal number 1..16 of the upper tooth touching there
  int lower_tooth = 0;  ///< Universal number 17..32 of the lower tooth touching there
};

struct SyntheticJawPair {
  /// Upper jaw in its own frame U. Parts: 0 = gingiva/base (tooth_number 0), then one part per
  /// tooth, Universal numbers 2..15 (patient's right second molar to left second molar).
  TriangleMesh upper_U;
  /// Lower jaw in frame L. Parts: 0 = gingiva/base, then teeth 18..31 (patient's left second
  /// molar to right second molar).
  TriangleMesh lower_L;
  /// Ground-truth pose of U in L: the bite (maximal intercuspation of the design).
  Eigen::Isometry3d X_LU = Eigen::Isometry3d::Identity();
  /// Where the arches touch at X_LU (a few per posterior tooth pair, both sides).
  std::vector<SyntheticContact> contacts;
  /// Unit occlusal axis in L, from the lower towards the upper jaw: +y.
  Eigen::Vector3d occlusal_axis_L = Eigen::Vector3d::UnitY();
};

/// Builds the synthetic jaw pair described above. Throws std::invalid_argument for options
/// outside their documented range. Single-threaded, no global state.
SyntheticJawPair MakeSyntheticJawPair(const SyntheticJawOptions& options);

}  // namespace occlude::io
