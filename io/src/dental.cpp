// Tooth numbers and landmark names (occlude/io/dental.h).
#include "occlude/io/dental.h"

#include <array>
#include <stdexcept>

namespace occlude::io {
namespace {

constexpr std::array<const char*, kNumLandmarkTypes> kLandmarkNames = {
    "mesial",   "distal",      "facial",       "lingual",      "incisal_edge",
    "cusp_tip", "buccal_cusp", "lingual_cusp", "mb_cusp",      "middle_buccal_cusp",
    "db_cusp",  "ml_cusp",     "dl_cusp",      "central_fossa"};

}  // namespace

const char* ToString(Jaw jaw) { return jaw == Jaw::kUpper ? "upper" : "lower"; }

std::optional<Jaw> JawFromName(const std::string& name) {
  if (name == "upper") return Jaw::kUpper;
  if (name == "lower") return Jaw::kLower;
  return std::nullopt;
}

bool IsValidFdi(int fdi) {
  const int quadrant = fdi / 10, position = fdi % 10;
  return quadrant >= 1 && quadrant <= 4 && position >= 1 && position <= 8;
}

Jaw JawOfFdi(int fdi) { return fdi / 10 <= 2 ? Jaw::kUpper : Jaw::kLower; }

int FdiFromUniversal(int universal) {
  if (universal < 1 || universal > 32) {
    throw std::invalid_argument("universal: tooth number " + std::to_string(universal) +
                                " is not a Universal number (1-32)");
  }
  if (universal <= 8) return 19 - universal;   // 1 -> 18 ... 8 -> 11
  if (universal <= 16) return 12 + universal;  // 9 -> 21 ... 16 -> 28
  if (universal <= 24) return 55 - universal;  // 17 -> 38 ... 24 -> 31
  return 16 + universal;                       // 25 -> 41 ... 32 -> 48
}

int UniversalFromFdi(int fdi) {
  if (!IsValidFdi(fdi)) {
    throw std::invalid_argument("fdi: tooth number " + std::to_string(fdi) +
                                " is not an FDI number (11-18, 21-28, 31-38, 41-48)");
  }
  const int quadrant = fdi / 10, position = fdi % 10;
  switch (quadrant) {
    case 1:
      return 9 - position;  // 18 -> 1 ... 11 -> 8
    case 2:
      return 8 + position;  // 21 -> 9 ... 28 -> 16
    case 3:
      return 25 - position;  // 31 -> 24 ... 38 -> 17
    default:
      return 24 + position;  // 41 -> 25 ... 48 -> 32
  }
}

const char* ToString(LandmarkType type) { return kLandmarkNames[static_cast<std::size_t>(type)]; }

std::optional<LandmarkType> LandmarkTypeFromName(const std::string& name) {
  for (std::size_t i = 0; i < kLandmarkNames.size(); ++i) {
    if (name == kLandmarkNames[i]) return static_cast<LandmarkType>(i);
  }
  return std::nullopt;
}

std::string LandmarkTypeNames() {
  std::string names;
  for (const char* name : kLandmarkNames) names += (names.empty() ? "" : ", ") + std::string(name);
  return names;
}

}  // namespace occlude::io
