// The procedural synthetic jaw pair: the project's embedded default for the demo, the tests
// and scaling studies. Deterministic (the same options give bit-identical meshes), fast (well
// under 2 s for 500,000 triangles per jaw) and anatomically plausible: a squared horseshoe arch
// of 14 teeth per jaw (central and lateral incisors with incisal edges, canines with one cusp,
// premolars with a buccal and a lingual cusp, first and second molars with four cusps, the lower
// first molar with five and its buccal groove) in a clinically normal Class I occlusion, with a
// known bite pose, known contact points, the clinical landmarks of every tooth and the
// relationships they make (../shared/docs/clinical.md).
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
// 60 x 54 mm in xz with gingiva. The lower arch is about 51 mm wide across its first molars
// (mesiobuccal cusp tips 45 mm apart, canine tips 28.5 mm) and 45 mm deep; it turns most at the
// canines and runs straight and parallel to z from the first molars back (within 1 deg of it
// from the distal half of the second premolars).
//
// The designed bite (seed 1; others within a few tenths): overjet 2.7 mm, overbite 2.2 mm,
// midline 0, molar and canine relationships 0 on both sides (Class I: the upper canine tip over
// the lower canine / first premolar embrasure, the upper first molar's mesiobuccal cusp over the
// lower first molar's buccal groove; exact up to the meshes' piecewise-linear surfaces, within
// 0.01 mm). It is the exact ground truth. Because the posterior segments are straight and
// parallel to z, the upper shifted mesially by a premolar width (class2_shift_L, 7 mm along +z:
// the full-cusp Class II finish, molar and canine relationships about +7 mm, overjet about
// 9.7 mm) slides along them and seats again: the upper surface also carries the record of that
// position (it is lifted wherever, so shifted, it would dip into the lower), so there it rests
// on the lower without interpenetrating and touches at spots on both sides' molars and second
// premolars. That alternative is a distinct local optimum of contact (a local search from starts
// near it returns to it) with 55-80 % of the bite's contact (seed 1 at 20,000 triangles: 77 %);
// it is found by search, not exact.
// The other way (upper distal, Class III) the incisors collide: no seat there.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "occlude/io/dental.h"
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

/// A measure on the patient's right and left sides.
struct SyntheticSides {
  double right = 0.0;
  double left = 0.0;
};

/// The clinical relationships the pair is designed with at X_LU (clinical.md's definitions and
/// signs applied to `landmarks`, in L: occlusal axis +y, anterior +z, lateral +x), mm.
struct SyntheticRelationships {
  double overjet_mm = 0.0;            ///< upper - lower central incisal edges along +z
  double overbite_mm = 0.0;           ///< lower - upper central incisal edges along +y
  double midline_deviation_mm = 0.0;  ///< upper - lower dental midline along +x
  SyntheticSides molar_mm;   ///< upper 16/26 mb cusp - lower 46/36 buccal groove, + upper mesial
  SyntheticSides canine_mm;  ///< upper 13/23 tip - lower 43/44 (33/34) embrasure, + upper mesial
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
  /// The landmarks of clinical.md on every tooth (FDI numbers), each a point of the final mesh
  /// surface: upper ones in U, lower ones in L. Per tooth: mesial, distal, facial, lingual;
  /// incisors incisal_edge; canines cusp_tip; premolars buccal_cusp, lingual_cusp and
  /// central_fossa; molars mb_cusp, db_cusp, ml_cusp, dl_cusp and central_fossa, and the lower
  /// first molars middle_buccal_cusp too (between mb_cusp and db_cusp, their distal cusp; its
  /// midpoint with mb_cusp is the buccal groove). Sorted by jaw (upper first) and FDI number.
  std::vector<Landmark> landmarks;
  /// The designed relationships at X_LU.
  SyntheticRelationships relationships;
  /// The full-cusp Class II alternative: X_LU moved by this translation in L (upper mesial by a
  /// premolar width) rests on the lower without interpenetrating (to within a few hundredths of
  /// a millimetre between mesh vertices) and touches at spots; a local search from there finds
  /// a seat with 55-80 % of the bite's contact. Not an exact ground truth: (0, 0, 7) mm.
  Eigen::Vector3d class2_shift_L = Eigen::Vector3d::Zero();
};

/// Builds the synthetic jaw pair described above. Throws std::invalid_argument for options
/// outside their documented range. Single-threaded, no global state.
SyntheticJawPair MakeSyntheticJawPair(const SyntheticJawOptions& options);

}  // namespace occlude::io
