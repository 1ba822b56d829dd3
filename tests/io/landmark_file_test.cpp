// The landmark file reader and writer: a well-formed file (blank lines, CRLF, byte-order mark,
// spaces around fields), the c-cases' files when present, and every kind of bad file rejected with
// one line naming the file, the line and the field; formatted landmarks read back.
#include "occlude/io/landmark_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "test_common.h"

namespace occlude::io {
namespace {

constexpr const char* kGood =
    "jaw,tooth,type,x_mm,y_mm,z_mm\n"
    "upper,11,incisal_edge,1.5,-2,3e-1\n"
    "\n"
    "lower, 46 ,mb_cusp,-30.25,+4,0\n";

TEST(LandmarkFileTest, ParsesRowsInOrder) {
  const std::vector<Landmark> l = ParseLandmarkFile(kGood, "good.csv");
  ASSERT_EQ(l.size(), 2u);
  EXPECT_EQ(l[0].jaw, Jaw::kUpper);
  EXPECT_EQ(l[0].tooth_fdi, 11);
  EXPECT_EQ(l[0].type, LandmarkType::kIncisalEdge);
  EXPECT_EQ(l[0].p, Eigen::Vector3d(1.5, -2.0, 0.3));
  EXPECT_EQ(l[1].jaw, Jaw::kLower);
  EXPECT_EQ(l[1].tooth_fdi, 46);
  EXPECT_EQ(l[1].type, LandmarkType::kMbCusp);
  EXPECT_EQ(l[1].p, Eigen::Vector3d(-30.25, 4.0, 0.0));
}

TEST(LandmarkFileTest, AcceptsCrLfAndByteOrderMarkAndAHeaderOnly) {
  std::string crlf = "\xEF\xBB\xBF";
  for (char c : std::string(kGood)) crlf += (c == '\n') ? std::string("\r\n") : std::string(1, c);
  EXPECT_EQ(ParseLandmarkFile(crlf, "crlf.csv").size(), 2u);
  EXPECT_TRUE(ParseLandmarkFile("jaw,tooth,type,x_mm,y_mm,z_mm\n", "h.csv").empty());
}

TEST(LandmarkFileTest, FormattedLandmarksReadBack) {
  const std::vector<Landmark> l = ParseLandmarkFile(kGood, "good.csv");
  const std::string text = FormatLandmarkFile(l);
  EXPECT_EQ(text.substr(0, text.find('\n')), kLandmarkFileHeader);
  const std::vector<Landmark> back = ParseLandmarkFile(text, "formatted.csv");
  ASSERT_EQ(back.size(), l.size());
  for (std::size_t i = 0; i < l.size(); ++i) {
    EXPECT_EQ(back[i].jaw, l[i].jaw);
    EXPECT_EQ(back[i].tooth_fdi, l[i].tooth_fdi);
    EXPECT_EQ(back[i].type, l[i].type);
    EXPECT_LT((back[i].p - l[i].p).norm(), 1e-6);
  }
}

TEST(LandmarkFileTest, ReadsAFileFromDisk) {
  test::TempDir dir;
  std::ofstream(dir / "landmarks.csv") << kGood;
  EXPECT_EQ(ReadLandmarkFile(dir / "landmarks.csv").size(), 2u);
}

TEST(LandmarkFileTest, ReadsTheCaseFiles) {
  for (const char* name :
       {"c1-ios-decimated", "c2-ios-decimated", "c3-ios-decimated", "c4-ios-decimated"}) {
    const auto folder = test::SharedCase(name);
    if (!folder) GTEST_SKIP() << "shared data case '" << name << "' not found";
    const std::vector<Landmark> l = ReadLandmarkFile(*folder / "landmarks.csv");
    EXPECT_EQ(l.size(), 192u) << name;  // 28 teeth, 4 surface points each plus the cusps
  }
}

struct BadFile {
  const char* name;
  const char* text;
  const char* expected;  // the message names this (line and field)
};

class LandmarkFileBadTest : public testing::TestWithParam<BadFile> {};

TEST_P(LandmarkFileBadTest, OneLineNamingFileLineAndField) {
  const BadFile& bad = GetParam();
  try {
    ParseLandmarkFile(bad.text, "case/landmarks.csv");
    FAIL() << "accepted " << bad.name;
  } catch (const LandmarkFileError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.rfind("case/landmarks.csv: ", 0), 0u) << what;
    EXPECT_NE(what.find(bad.expected), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Issue19, LandmarkFileBadTest,
    testing::Values(
        BadFile{"empty", "", "empty"},
        BadFile{"wrong_header", "jaw,tooth,kind,x,y,z\nupper,11,mesial,1,2,3\n", "line 1: header"},
        BadFile{"missing_column", "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,11,mesial,1,2\n",
                "line 2: z_mm: missing column"},
        BadFile{"extra_column", "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,11,mesial,1,2,3,4\n",
                "line 2: 7 fields"},
        BadFile{"unknown_jaw", "jaw,tooth,type,x_mm,y_mm,z_mm\nmiddle,11,mesial,1,2,3\n",
                "line 2: jaw: 'middle'"},
        BadFile{"unknown_tooth", "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,19,mesial,1,2,3\n",
                "line 2: tooth: '19'"},
        BadFile{"tooth_not_a_number", "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,1a,mesial,1,2,3\n",
                "line 2: tooth: '1a'"},
        BadFile{"tooth_of_other_jaw", "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,31,mesial,1,2,3\n",
                "line 2: tooth: 31 is a lower tooth"},
        BadFile{"unknown_type", "jaw,tooth,type,x_mm,y_mm,z_mm\n\nupper,11,cusp,1,2,3\n",
                "line 3: type: 'cusp'"},
        BadFile{"nan_coordinate", "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,11,mesial,1,nan,3\n",
                "line 2: y_mm: 'nan' is not a finite number"},
        BadFile{"inf_coordinate", "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,11,mesial,inf,2,3\n",
                "line 2: x_mm: 'inf'"},
        BadFile{"empty_coordinate", "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,11,mesial,1,2,\n",
                "line 2: z_mm: ''"},
        BadFile{"duplicate",
                "jaw,tooth,type,x_mm,y_mm,z_mm\nupper,11,mesial,1,2,3\nupper,11,mesial,1,2,3\n",
                "line 3: landmark upper 11 mesial is given twice (first on line 2)"}),
    [](const testing::TestParamInfo<BadFile>& param) { return std::string(param.param.name); });

TEST(LandmarkFileTest, MissingFileAndFolderAreNamed) {
  test::TempDir dir;
  try {
    ReadLandmarkFile(dir / "none.csv");
    FAIL();
  } catch (const LandmarkFileError& e) {
    EXPECT_NE(std::string(e.what()).find("none.csv: no such file"), std::string::npos) << e.what();
  }
  try {
    ReadLandmarkFile(dir.path());
    FAIL();
  } catch (const LandmarkFileError& e) {
    EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace occlude::io
