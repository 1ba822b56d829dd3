// Tooth layout of the synthetic jaw pair: mesiodistal and buccolingual crown sizes, crown
// heights and cusps of the 14 teeth per jaw, placed along the arch in Class I interdigitation
// (upper and lower teeth laid out from a common midline with their own widths, so each upper
// posterior tooth sits about half a premolar distal of its lower namesake and occludes with
// two lower teeth). The seed jitters sizes and heights slightly, deterministically.
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
constexpr std::array<double, kNumToothClasses> kUpperTipY = {-2.5, -2.0, -2.3, -1.5,
                                                             -1.5, -1.5, -1.5};
constexpr double kUpperPosteriorTipY = -1.5;  // U's origin level
// Upper crowns are centred buccally of the lower ones (upper arch wider: overjet).
constexpr std::array<double, kNumToothClasses> kUpperCenterT = {2.6, 2.4, 2.2, 1.8, 1.8, 1.8, 1.8};
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
/// (-1 lingual .. +1 buccal), amplitude mm.
struct CuspSpec {
  double m, v, amplitude;
};

struct ClassMorphology {
  std::vector<CuspSpec> cusps;
  double sigma = 1.3;  // mm
};

// Cusps: tips, in (m, v, amplitude mm); lower premolars buccal + lingual, upper premolars
// buccal + palatal; canines one pointed cusp; incisors have an incisal edge instead.
ClassMorphology LowerMorphology(int cls) {
  switch (cls) {
    case kCanine:
      return {{{0.0, 0.1, 2.8}}, 1.8};
    case kFirstPremolar:
      return {{{0.0, 0.4, 2.2}, {0.0, -0.55, 1.2}}, 1.4};
    case kSecondPremolar:
      return {{{0.0, 0.4, 2.2}, {0.0, -0.5, 1.7}}, 1.4};
    case kFirstMolar:
      return {{{-0.55, 0.5, 2.2},   // mesiobuccal
               {0.0, 0.5, 2.2},     // distobuccal
               {0.55, 0.45, 1.9},   // distal
               {-0.45, -0.5, 2.2},  // mesiolingual
               {0.35, -0.5, 2.1}},  // distolingual
              1.35};
    case kSecondMolar:
      return {{{-0.45, 0.5, 2.2},   // mesiobuccal
               {0.45, 0.5, 2.1},    // distobuccal
               {-0.45, -0.5, 2.2},  // mesiolingual
               {0.45, -0.5, 2.0}},  // distolingual
              1.35};
    default:
      return {};
  }
}

ClassMorphology UpperMorphology(int cls) {
  switch (cls) {
    case kCanine:
      return {{{0.0, 0.15, 2.8}}, 1.8};
    case kFirstPremolar:
      return {{{0.0, 0.45, 2.2}, {0.0, -0.45, 1.9}}, 1.4};
    case kSecondPremolar:
      return {{{0.0, 0.45, 2.1}, {0.0, -0.45, 2.1}}, 1.4};
    case kFirstMolar:
      return {{{-0.45, 0.5, 2.2},   // mesiobuccal
               {0.4, 0.5, 2.1},     // distobuccal
               {-0.3, -0.45, 2.4},  // mesiopalatal (the largest, seats in the lower fossa)
               {0.45, -0.5, 1.7}},  // distopalatal
              1.35};
    case kSecondMolar:
      return {{{-0.4, 0.5, 2.2},    // mesiobuccal
               {0.4, 0.45, 1.9},    // distobuccal
               {-0.2, -0.45, 2.2},  // mesiopalatal
               {0.45, -0.5, 1.4}},  // distopalatal
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
void AddMorphology(bool upper, int side, double cusp_jitter_scale, Jitter& jitter, Tooth& tooth) {
  const int cls = tooth.tooth_class;
  if (cls == kCentralIncisor || cls == kLateralIncisor) {
    tooth.edge_v = upper ? 0.45 : 0.0;
    tooth.edge_lingual = upper ? 2.5 : 2.0;
    tooth.edge_buccal = upper ? 4.0 : 2.0;
    return;
  }
  const ClassMorphology morph = upper ? UpperMorphology(cls) : LowerMorphology(cls);
  const double half_md = tooth.half_length / kProximalOverlap;
  double highest = 0.0;
  for (const CuspSpec& c : morph.cusps) {
    Cusp cusp;
    cusp.s = tooth.s_center + side * c.m * half_md;
    cusp.t = tooth.t_center + c.v * tooth.half_width;
    cusp.amplitude = c.amplitude * (1.0 + cusp_jitter_scale * jitter.Next());
    cusp.sigma = morph.sigma;
    highest = std::max(highest, cusp.amplitude);
    tooth.cusps.push_back(cusp);
  }
  tooth.relief_cap = kReliefCap * highest;
  tooth.relief_floor = kReliefFloor * highest;
}

/// The 14 crowns of one jaw, laid out from the midline with the class widths (jittered).
JawLayout MakeJaw(bool upper, Jitter& jitter) {
  JawLayout jaw;
  jaw.gingiva_y = upper ? kUpperGingivaY : kLowerGingivaY;
  for (const int side : {-1, 1}) {
    double s_mesial = 0.0;  // |s| of the current tooth's mesial end
    for (int cls = 0; cls < kNumToothClasses; ++cls) {
      Tooth tooth;
      tooth.tooth_class = static_cast<ToothClass>(cls);
      tooth.number = UniversalNumber(upper, side, cls);
      const double md = (upper ? kUpperMesiodistal : kLowerMesiodistal)[cls] *
                        (1.0 + kWidthJitter * jitter.Next());
      const double bl = (upper ? kUpperBuccolingual : kLowerBuccolingual)[cls] *
                        (1.0 + kWidthJitter * jitter.Next());
      const double height_scale = 1.0 + kHeightJitter * jitter.Next();
      tooth.s_center = side * (s_mesial + 0.5 * md);
      tooth.half_length = 0.5 * md * kProximalOverlap;
      tooth.t_center = upper ? kUpperCenterT[cls] : 0.0;
      tooth.half_width = 0.5 * bl;
      tooth.crown_height = upper ? (kUpperGingivaY - kUpperTipY[cls]) * height_scale
                                 : kLowerCrownHeight[cls] * height_scale;
      AddMorphology(upper, side, kCuspJitter, jitter, tooth);
      jaw.teeth.push_back(tooth);
      s_mesial += md;
    }
  }
  std::sort(jaw.teeth.begin(), jaw.teeth.end(),
            [](const Tooth& a, const Tooth& b) { return a.s_center < b.s_center; });
  return jaw;
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

}  // namespace

DentitionLayout MakeDentitionLayout(std::uint32_t seed) {
  Jitter jitter(seed);
  DentitionLayout layout;
  layout.lower = MakeJaw(/*upper=*/false, jitter);
  layout.upper = MakeJaw(/*upper=*/true, jitter);
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
