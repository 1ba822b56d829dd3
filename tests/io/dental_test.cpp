// Tooth numbering and landmark names: the FDI <-> Universal map against the charts of
// clinical.md (both ends of every quadrant), round trips over every tooth, and name parsing.
#include "occlude/io/dental.h"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>

namespace occlude::io {
namespace {

TEST(DentalTest, UniversalToFdiMatchesTheChart) {
  EXPECT_EQ(FdiFromUniversal(1), 18);  // upper right third molar
  EXPECT_EQ(FdiFromUniversal(8), 11);  // upper right central incisor
  EXPECT_EQ(FdiFromUniversal(9), 21);
  EXPECT_EQ(FdiFromUniversal(16), 28);
  EXPECT_EQ(FdiFromUniversal(17), 38);  // lower left third molar
  EXPECT_EQ(FdiFromUniversal(24), 31);
  EXPECT_EQ(FdiFromUniversal(25), 41);
  EXPECT_EQ(FdiFromUniversal(32), 48);
  EXPECT_EQ(FdiFromUniversal(3), 16);   // upper right first molar
  EXPECT_EQ(FdiFromUniversal(19), 36);  // lower left first molar
}

TEST(DentalTest, EveryToothRoundTripsAndHasItsJawAndSide) {
  std::set<int> seen;
  for (int u = 1; u <= 32; ++u) {
    const int fdi = FdiFromUniversal(u);
    ASSERT_TRUE(IsValidFdi(fdi)) << u;
    EXPECT_EQ(UniversalFromFdi(fdi), u);
    EXPECT_EQ(JawOfFdi(fdi), u <= 16 ? Jaw::kUpper : Jaw::kLower) << u;
    // Universal runs right to left in the upper jaw, left to right in the lower.
    const bool left = (u >= 9 && u <= 24);
    EXPECT_EQ(IsLeftSide(fdi), left) << u;
    seen.insert(fdi);
  }
  EXPECT_EQ(seen.size(), 32u);
}

TEST(DentalTest, InvalidNumbersAreRejectedNamingTheField) {
  for (int fdi : {0, 10, 19, 50, 49, -11}) EXPECT_FALSE(IsValidFdi(fdi)) << fdi;
  EXPECT_THROW(FdiFromUniversal(0), std::invalid_argument);
  EXPECT_THROW(FdiFromUniversal(33), std::invalid_argument);
  try {
    UniversalFromFdi(19);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("fdi"), std::string::npos);
  }
}

TEST(DentalTest, LandmarkNamesRoundTrip) {
  for (int i = 0; i < kNumLandmarkTypes; ++i) {
    const auto type = static_cast<LandmarkType>(i);
    EXPECT_EQ(LandmarkTypeFromName(ToString(type)), type);
  }
  EXPECT_EQ(std::string(ToString(LandmarkType::kMbCusp)), "mb_cusp");
  EXPECT_FALSE(LandmarkTypeFromName("mb-cusp").has_value());
  EXPECT_NE(LandmarkTypeNames().find("central_fossa"), std::string::npos);
  EXPECT_EQ(JawFromName("upper"), Jaw::kUpper);
  EXPECT_FALSE(JawFromName("Upper").has_value());
}

}  // namespace
}  // namespace occlude::io
