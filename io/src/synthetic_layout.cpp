// Tooth layout of the synthetic jaw pair: mesiodistal and buccolingual crown sizes, crown
// heights and cusps of the 14 teeth per jaw, placed along the arch in Class I occlusion. The
// lower teeth are laid out from the midline with their own widths; the upper ones are anchored
// on them per side (clinical.md, Andrews' key I): the upper canine tip over the embrasure of the
// lower canine and first premolar, the mesiobuccal cusp of the upper first molar over the
// buccal groove of the lower first molar, the upper incisors and premolars filling the spans in
// between, so each upper posterior tooth sits about half a premolar distal of its lower
// namesake and occludes with two lower teeth. The seed jitters sizes and heights slightly,
// deterministically.
#include <algorithm>
#include <array>

#include "synthetic_jaws_internal.h"

namespace occlude::io::synthetic {
namespace {

// Per tooth class, central incisor .. second molar (mm).
constexpr std::array<double, kNumToothClasses> kUpperMesiodistal = {8.5, 6.5,  7.5, 7.0,
                                                                    6.5, 10.0, 9.0};
constexpr std::array<double, kNumToothClasses> kLowerMesiodistal = {5.5, 6.0,  7.0, 7.0,
                                                                    7.0, 11.0, 10.5};
constexpr std::array<double, kNumToothClasses> kUpperBuccolingual = {7.0, 6.5,  8.0, 9.0,
                                                                     9.0, 11.0, 10.5};
constexpr std::array<double, kNumToothClasses> kLowerBuccolingual = {6.0, 6.0,  7.5, 7.5,
                                                                     8.0, 10.5, 10.0};
// Lower crowns rise from the gingiva at y = kLowerGingivaY to their tips near y = 0 (the
// occlusal plane of L); upper crowns hang from y = kUpperGingivaY to the levels below, which
// overlap the lower crowns vertically (overbite) as in a real bite.
constexpr double kLowerGingivaY = -6.0;
constexpr double kUpperGingivaY = 5.0;
constexpr std::array<double, kNumToothClasses> kLowerCrownHeight = {6.0, 6.0, 6.3, 6.0,
                                                                    6.0, 6.0, 6.0};
constexpr std::array<double, kNumToothClasses> kUpperTipY = {-2.3, -2.1, -2.2, -1.5,
                                                             -1.5, -1.5, -1.5};
constexpr double kUpperPosteriorTipY = -1.5;  // U's origin level
// Upper crowns are centred buccally of the lower ones (upper arch wider: overjet), the incisal
// edges and the canine tip far enough out that they hang clear of the lower labial faces.
constexpr std::array<double, kNumToothClasses> kUpperCenterT = {1.2, 1.1, 2.8, 1.8, 1.8, 1.8, 1.8};
constexpr double kProximalOverlap = 1.12;  // crowns reach past their span into the neighbour's
constexpr double kGingivaMargin = 2.5;     // mm of gingiva beyond the crowns, all around
constexpr double kBackThickness = 8.0;     // mm from the gingiva to the flat back of a slab

// Occlusal relief: cusp bumps clamped to [kReliefFloor, kReliefCap] x the highest cusp (flat
// worn cusp tips about 0.9 mm across and flat fossa floors: where opposing cusps rest).
constexpr double kReliefCap = 0.8;
constexpr double kReliefFloor = 0.3;

// Jitter amplitudes (relative).
constexpr double kWidthJitter = 0.03;
constexpr double kHeightJitter = 0.04;
constexpr double kCuspJitter = 0.10;

/// Cusp in crown-normalised coordinates: m along the arch (-1 mesial .. +1 distal), v across
/// (-1 lingual .. +1 buccal), amplitude mm, and its landmark type.
struct CuspSpec {
  double m, v, amplitude;
  LandmarkType type;
};

struct ClassMorphology {
  std::vector<CuspSpec> cusps;
  double sigma = 1.3;  // mm
};

using LT = LandmarkType;

// The mesiobuccal cusp of the upper first molar and the two lower first molar cusps whose
// midpoint is the buccal groove (the molar relationship's landmarks).
constexpr double kUpperFirstMolarMbM = -0.45;
constexpr double kLowerFirstMolarMbM = -0.5;
constexpr double kLowerFirstMolarMiddleM = 0.05;

// Cusps: tips, in (m, v, amplitude mm); lower premolars buccal + lingual, upper premolars
// buccal + palatal; canines one pointed cusp; incisors have an incisal edge instead. Every tip
// lies within the crown's flat core (|v| <= kBuccolingualCore, |m| / kProximalOverlap <=
// kMesiodistalCore of synthetic_crowns.cpp), so its worn-flat top is the crown's extreme there.
ClassMorphology LowerMorphology(int cls) {
  switch (cls) {
    case kCanine:
      return {{{0.0, 0.1, 2.8, LT::kCuspTip}}, 1.8};
    case kFirstPremolar:
      return {{{0.0, 0.4, 2.2, LT::kBuccalCusp}, {0.0, -0.45, 1.2, LT::kLingualCusp}}, 1.4};
    case kSecondPremolar:
      return {{{0.0, 0.4, 2.2, LT::kBuccalCusp}, {0.0, -0.45, 1.7, LT::kLingualCusp}}, 1.4};
    case kFirstMolar:
      return {{{kLowerFirstMolarMbM, 0.45, 2.2, LT::kMbCusp},
               {kLowerFirstMolarMiddleM, 0.45, 2.2, LT::kMiddleBuccalCusp},
               {0.6, 0.45, 1.9, LT::kDbCusp},  // the distal cusp
               {-0.45, -0.45, 2.2, LT::kMlCusp},
               {0.35, -0.45, 2.1, LT::kDlCusp}},
              1.35};
    case kSecondMolar:
      return {{{-0.45, 0.45, 2.2, LT::kMbCusp},
               {0.45, 0.45, 2.1, LT::kDbCusp},
               {-0.45, -0.45, 2.2, LT::kMlCusp},
               {0.45, -0.45, 2.0, LT::kDlCusp}},
              1.35};
    default:
      return {};
  }
}

ClassMorphology UpperMorphology(int cls) {
  switch (cls) {
    case kCanine:
      return {{{0.0, 0.15, 2.8, LT::kCuspTip}}, 1.8};
    case kFirstPremolar:
      return {{{0.0, 0.45, 2.2, LT::kBuccalCusp}, {0.0, -0.45, 1.9, LT::kLingualCusp}}, 1.4};
    case kSecondPremolar:
      return {{{0.0, 0.45, 2.1, LT::kBuccalCusp}, {0.0, -0.45, 2.1, LT::kLingualCusp}}, 1.4};
    case kFirstMolar:
      return {{{kUpperFirstMolarMbM, 0.45, 2.2, LT::kMbCusp},
               {0.4, 0.45, 2.1, LT::kDbCusp},
               {-0.3, -0.45, 2.4, LT::kMlCusp},  // mesiopalatal: the largest, in the lower fossa
               {0.45, -0.45, 1.7, LT::kDlCusp}},
              1.35};
    case kSecondMolar:
      return {{{-0.4, 0.45, 2.2, LT::kMbCusp},
               {0.4, 0.45, 1.9, LT::kDbCusp},
               {-0.2, -0.45, 2.2, LT::kMlCusp},
               {0.45, -0.45, 1.4, LT::kDlCusp}},
              1.35};
    default:
      return {};
  }
}

/// SplitMix64: a tiny generator whose draws, unlike the std:: distributions', are the same
/// with every standard library.
class Jitter {
 public:
  explicit Jitter(std::uint32_t seed) : state_(0x9E3779B97F4A7C15ULL * (seed + 1ULL)) {}
  /// Uniform in [-1, 1).
  double Next() {
    state_ += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;
  }

 private:
  std::uint64_t state_;
};

int UniversalNumber(bool upper, int side, int cls) {
  if (upper) return side > 0 ? 9 + cls : 8 - cls;
  return side > 0 ? 24 - cls : 25 + cls;
}

/// Fills the incisal edge or the cusps of `tooth` (its centre and sizes already set).
void AddMorphology(bool upper, Jitter& jitter, Tooth& tooth) {
  const int cls = tooth.tooth_class;
  if (cls == kCentralIncisor || cls == kLateralIncisor) {
    tooth.edge_v = upper ? 0.4 : 0.0;
    tooth.edge_lingual = upper ? 2.5 : 2.0;
    tooth.edge_buccal = upper ? 4.0 : 2.0;
    return;
  }
  const ClassMorphology morph = upper ? UpperMorphology(cls) : LowerMorphology(cls);
  const double half_md = tooth.half_length / kProximalOverlap;
  double highest = 0.0;
  for (const CuspSpec& c : morph.cusps) {
    Cusp cusp;
    cusp.s = tooth.s_center + tooth.side * c.m * half_md;
    cusp.t = tooth.t_center + c.v * tooth.half_width;
    cusp.amplitude = c.amplitude * (1.0 + kCuspJitter * jitter.Next());
    cusp.sigma = morph.sigma;
    cusp.type = c.type;
    highest = std::max(highest, cusp.amplitude);
    tooth.cusps.push_back(cusp);
  }
  tooth.relief_cap = kReliefCap * highest;
  tooth.relief_floor = kReliefFloor * highest;
}

/// Jittered crown sizes of one tooth, mm (mesiodistal, buccolingual) and its height scale.
struct CrownSize {
  double md = 0.0, bl = 0.0, height_scale = 1.0;
};
CrownSize DrawSize(bool upper, int cls, Jitter& jitter) {
  CrownSize size;
  size.md =
      (upper ? kUpperMesiodistal : kLowerMesiodistal)[cls] * (1.0 + kWidthJitter * jitter.Next());
  size.bl =
      (upper ? kUpperBuccolingual : kLowerBuccolingual)[cls] * (1.0 + kWidthJitter * jitter.Next());
  size.height_scale = 1.0 + kHeightJitter * jitter.Next();
  return size;
}

/// The crown of class `cls` on `side` spanning |s| in [mesial, mesial + md].
Tooth MakeTooth(bool upper, int side, int cls, double mesial, double md, const CrownSize& size,
                Jitter& jitter) {
  Tooth tooth;
  tooth.tooth_class = static_cast<ToothClass>(cls);
  tooth.number = UniversalNumber(upper, side, cls);
  tooth.side = side;
  tooth.s_mesial = side * mesial;
  tooth.s_distal = side * (mesial + md);
  tooth.s_center = side * (mesial + 0.5 * md);
  tooth.half_length = 0.5 * md * kProximalOverlap;
  tooth.t_center = upper ? kUpperCenterT[cls] : 0.0;
  tooth.half_width = 0.5 * size.bl;
  tooth.crown_height = upper ? (kUpperGingivaY - kUpperTipY[cls]) * size.height_scale
                             : kLowerCrownHeight[cls] * size.height_scale;
  AddMorphology(upper, jitter, tooth);
  return tooth;
}

/// The seven lower crowns of one side, laid out from the midline with their own widths.
void AddLowerSide(int side, Jitter& jitter, std::vector<Tooth>* teeth) {
  double mesial = 0.0;  // |s| of the current tooth's mesial end
  for (int cls = 0; cls < kNumToothClasses; ++cls) {
    const CrownSize size = DrawSize(false, cls, jitter);
    teeth->push_back(MakeTooth(false, side, cls, mesial, size.md, size, jitter));
    mesial += size.md;
  }
}

const Tooth& Find(const std::vector<Tooth>& teeth, int side, int cls) {
  for (const Tooth& tooth : teeth) {
    if (tooth.side == side && tooth.tooth_class == cls) return tooth;
  }
  return teeth.front();  // not reached: every class exists on both sides
}

/// Where on the straight posterior segment the lower first molar's buccal groove lies, |s| mm.
double LowerBuccalGroove(const Tooth& molar) {
  const double half_md = molar.half_length / kProximalOverlap;
  return std::abs(molar.s_center) + 0.5 * (kLowerFirstMolarMbM + kLowerFirstMolarMiddleM) * half_md;
}

/// |s| of an upper canine tip at t = tip_t in Class I: its offset from the embrasure of the lower
/// canine and first premolar along the lower canine's mesio-distal direction, in the occlusal
/// plane (clinical.md's canine relationship), is 0. Secant iterations on the arch curve.
double ClassOneCanineTip(const ArchCurve& arch, const Tooth& lower_canine, double tip_t) {
  const Eigen::Vector2d embrasure = ArchPoint(arch, lower_canine.s_distal);
  const Eigen::Vector2d mesial = (ArchPoint(arch, lower_canine.s_mesial) - embrasure).normalized();
  const auto offset = [&](double s) {
    const double signed_s = lower_canine.side * s;
    const Eigen::Vector2d tip = ArchPoint(arch, signed_s) + tip_t * ArchNormal(arch, signed_s);
    return (tip - embrasure).dot(mesial);
  };
  double a = std::abs(lower_canine.s_distal), b = a + 0.1;
  double fa = offset(a), fb = offset(b);
  for (int k = 0; k < 20 && fb != fa && std::abs(fb) > 1e-12; ++k) {
    const double c = b - fb * (b - a) / (fb - fa);
    a = b;
    fa = fb;
    b = c;
    fb = offset(b);
  }
  return b;
}

/// The seven upper crowns of one side in Class I on `lower`: canine tip over the lower canine /
/// first premolar embrasure, first molar mesiobuccal cusp over the lower buccal groove;
/// incisors and premolars scaled to fit between.
void AddUpperSide(const ArchCurve& arch, int side, const std::vector<Tooth>& lower, Jitter& jitter,
                  std::vector<Tooth>* teeth) {
  std::array<CrownSize, kNumToothClasses> size;
  for (int cls = 0; cls < kNumToothClasses; ++cls) size[cls] = DrawSize(true, cls, jitter);
  const double tip_t =
      kUpperCenterT[kCanine] + UpperMorphology(kCanine).cusps.front().v * 0.5 * size[kCanine].bl;
  const double canine_tip = ClassOneCanineTip(arch, Find(lower, side, kCanine), tip_t);
  const double groove = LowerBuccalGroove(Find(lower, side, kFirstMolar));
  const double molar_mesial = groove - (1.0 + kUpperFirstMolarMbM) * 0.5 * size[kFirstMolar].md;
  const double canine_mesial = canine_tip - 0.5 * size[kCanine].md;
  const double canine_distal = canine_tip + 0.5 * size[kCanine].md;
  const double incisors = canine_mesial / (size[kCentralIncisor].md + size[kLateralIncisor].md);
  const double premolars =
      (molar_mesial - canine_distal) / (size[kFirstPremolar].md + size[kSecondPremolar].md);
  double mesial = 0.0;
  for (int cls = 0; cls < kNumToothClasses; ++cls) {
    double md = size[cls].md;
    if (cls <= kLateralIncisor) md *= incisors;
    if (cls == kFirstPremolar || cls == kSecondPremolar) md *= premolars;
    teeth->push_back(MakeTooth(true, side, cls, mesial, md, size[cls], jitter));
    mesial += md;
  }
}

/// Extends [lo, hi] (s or t) to cover every crown of `jaw`.
void CoverCrowns(const JawLayout& jaw, double* s_lo, double* s_hi, double* t_lo, double* t_hi) {
  for (const Tooth& tooth : jaw.teeth) {
    *s_lo = std::min(*s_lo, tooth.s_center - tooth.half_length);
    *s_hi = std::max(*s_hi, tooth.s_center + tooth.half_length);
    *t_lo = std::min(*t_lo, tooth.t_center - tooth.half_width);
    *t_hi = std::max(*t_hi, tooth.t_center + tooth.half_width);
  }
}

void SortByS(JawLayout* jaw) {
  std::sort(jaw->teeth.begin(), jaw->teeth.end(),
            [](const Tooth& a, const Tooth& b) { return a.s_center < b.s_center; });
}

}  // namespace

DentitionLayout MakeDentitionLayout(std::uint32_t seed) {
  Jitter jitter(seed);
  DentitionLayout layout;
  layout.lower.gingiva_y = kLowerGingivaY;
  layout.upper.gingiva_y = kUpperGingivaY;
  for (const int side : {-1, 1}) AddLowerSide(side, jitter, &layout.lower.teeth);
  for (const int side : {-1, 1}) {
    AddUpperSide(layout.arch, side, layout.lower.teeth, jitter, &layout.upper.teeth);
  }
  SortByS(&layout.lower);
  SortByS(&layout.upper);
  double s_lo = 0.0, s_hi = 0.0, t_lo = 0.0, t_hi = 0.0;
  CoverCrowns(layout.lower, &s_lo, &s_hi, &t_lo, &t_hi);
  CoverCrowns(layout.upper, &s_lo, &s_hi, &t_lo, &t_hi);
  layout.s_min = s_lo - kGingivaMargin;
  layout.s_max = s_hi + kGingivaMargin;
  layout.t_min = t_lo - kGingivaMargin;
  layout.t_max = t_hi + kGingivaMargin;
  layout.lower_base_y = kLowerGingivaY - kBackThickness;
  layout.upper_top_y = kUpperGingivaY + kBackThickness;
  layout.upper_origin_y = kUpperPosteriorTipY;
  // Centre the dentition on z = 0: incisal edges at +depth/2, distal molar ends at -depth/2.
  const double distal = std::max(-s_lo, s_hi);
  layout.arch.z_offset = -0.5 * ArchPoint(layout.arch, distal).y();
  return layout;
}

}  // namespace occlude::io::synthetic
