// The one loader of jaw pairs: case folders (named after the folder, at the identity bite;
// errors naming the folder or the missing file), one jaw from a file or from part files (tooth
// numbers from the names, units converted), the synthetic pair at its designed bite, a case
// config's meshes, and the re-expression at the reference pose a case session works in.
#include "session/jaw_pair.h"

#include <gtest/gtest.h>

#include <string>

#include "base/user_error.h"
#include "occlude/io/mesh_io.h"
#include "occlude/io/synthetic_jaws.h"
#include "test_common.h"

namespace occlude::test {
namespace {

// Errors are one line naming the file or folder; `expected` is part of it.
template <class F>
void ExpectUserError(F&& load, const std::string& expected) {
  try {
    load();
    ADD_FAILURE() << "no error, expected '" << expected << "'";
  } catch (const app::UserError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(JawPairTest, CaseFolderIsNamedAfterItsFolderAtTheIdentityBite) {
  TempDir tmp;
  std::filesystem::create_directories(tmp / "bite");
  io::WriteBinaryStl(MakeBox({0, 0, 0}, {10, 4, 6}), tmp / "bite" / "lower.stl");
  io::WriteBinaryStl(MakeBox({0, 4, 0}, {10, 8, 6}), tmp / "bite" / "upper.stl");
  for (const std::filesystem::path& dir : {tmp / "bite", tmp / "bite" / ""}) {
    const app::JawPair pair = app::LoadCaseFolder(dir);
    EXPECT_EQ(pair.name, "bite") << dir;
    EXPECT_TRUE(pair.X_LU_ref.isApprox(Eigen::Isometry3d::Identity(), 0.0));
    EXPECT_EQ(pair.lower_L->num_triangles(), 12u);
    EXPECT_NEAR(pair.upper_U->Bounds().min().y(), 4.0, 1e-6);
    EXPECT_FALSE(pair.occlusal_axis_L.has_value());
  }
}

TEST(JawPairTest, CaseFolderErrorsNameTheFolderOrTheMissingFile) {
  TempDir tmp;
  ExpectUserError([&] { app::LoadCaseFolder(tmp / "nothere"); },
                  "--case: '" + (tmp / "nothere").string() + "' is not a folder");
  std::filesystem::create_directories(tmp / "empty");
  ExpectUserError([&] { app::LoadCaseFolder(tmp / "empty"); },
                  "lower.stl: not found (a case folder holds upper.stl and lower.stl)");
  ExpectUserError([&] { app::LoadCaseFolder(tmp / "empty", "what the command needs"); },
                  "lower.stl: not found (what the command needs)");
}

TEST(JawPairTest, PartFilesCarryTheirToothNumbersAndUnitsConvert) {
  TempDir tmp;
  io::WriteBinaryStl(MakeBox({0, 0, 0}, {1, 1, 1}), tmp / "Tooth_14.stl");
  io::WriteBinaryStl(MakeBox({2, 0, 0}, {3, 1, 1}), tmp / "Tooth_3.stl");
  const auto jaw = app::LoadJaw({tmp / "Tooth_14.stl", tmp / "Tooth_3.stl"}, true);
  ASSERT_EQ(jaw->parts.size(), 2u);
  EXPECT_EQ(jaw->parts[0].tooth_number, 14);
  EXPECT_EQ(jaw->parts[1].tooth_number, 3);
  const auto in_cm = app::LoadJaw({tmp / "Tooth_3.stl"}, false, io::LengthUnit::kCentimetre);
  EXPECT_NEAR(in_cm->Bounds().max().x(), 30.0, 1e-5);
  ExpectUserError([&] { app::LoadJaw({tmp / "none.stl"}, false); }, "none.stl");
}

TEST(JawPairTest, SyntheticPairIsAtItsDesignedBite) {
  io::SyntheticJawOptions options;
  options.triangles_per_jaw = io::kMinSyntheticTriangles;
  options.seed = 2;
  const io::SyntheticJawPair jaws = io::MakeSyntheticJawPair(options);
  const app::JawPair pair = app::SyntheticJawPair(io::kMinSyntheticTriangles, 2);
  EXPECT_EQ(pair.name, "synthetic-" + std::to_string(io::kMinSyntheticTriangles));
  EXPECT_TRUE(pair.X_LU_ref.isApprox(jaws.X_LU, 0.0));
  EXPECT_EQ(pair.upper_U->vertices, jaws.upper_U.vertices);
  ASSERT_TRUE(pair.occlusal_axis_L.has_value());
  EXPECT_TRUE(pair.occlusal_axis_L->isApprox(jaws.occlusal_axis_L, 0.0));
  EXPECT_EQ(pair.truth_contacts_L.size(), jaws.contacts.size());
  ExpectUserError([] { app::SyntheticJawPair(10, 1); }, "--triangles");
}

TEST(JawPairTest, AtReferenceMovesTheUpperIntoTheLowerFrame) {
  const app::JawPair pair = app::SyntheticJawPair(io::kMinSyntheticTriangles, 1);
  const app::JawPair at = app::AtReference(pair);
  EXPECT_TRUE(at.X_LU_ref.isApprox(Eigen::Isometry3d::Identity(), 0.0));
  ASSERT_EQ(at.upper_U->num_vertices(), pair.upper_U->num_vertices());
  for (std::size_t i = 0; i < at.upper_U->num_vertices(); i += 97) {
    EXPECT_TRUE(at.upper_U->vertices[i].isApprox(pair.X_LU_ref * pair.upper_U->vertices[i], 1e-12));
  }
  EXPECT_EQ(at.lower_L, pair.lower_L);
  EXPECT_EQ(at.truth_contacts_L, pair.truth_contacts_L);  // in L: unchanged
  const app::JawPair again = app::AtReference(at);        // already at identity: as it is
  EXPECT_EQ(again.upper_U, at.upper_U);
}

TEST(JawPairTest, ConfigMeshesAreTheFilesOrTheSyntheticPair) {
  TempDir tmp;
  io::WriteBinaryStl(MakeBox({0, 0, 0}, {1, 1, 1}), tmp / "lower.stl");
  io::WriteBinaryStl(MakeBox({0, 1, 0}, {1, 2, 1}), tmp / "upper.stl");
  const app::CaseConfig files = app::ParseCaseConfig(
      "[case]\nunits = \"cm\"\n[lower]\nfile = \"lower.stl\"\n[upper]\nfile = \"upper.stl\"\n",
      tmp / "case.toml");
  const app::JawPair pair = app::LoadConfigJaws(files);
  EXPECT_EQ(pair.name, "case");
  EXPECT_NEAR(pair.upper_U->Bounds().max().y(), 20.0, 1e-5);
  const app::CaseConfig synthetic =
      app::ParseCaseConfig("[synthetic]\ntriangles = 5000\nseed = 3\n", tmp / "s.toml");
  const app::JawPair generated = app::LoadConfigJaws(synthetic);
  EXPECT_EQ(generated.upper_U->vertices, app::SyntheticJawPair(5000, 3).upper_U->vertices);
}

}  // namespace
}  // namespace occlude::test
