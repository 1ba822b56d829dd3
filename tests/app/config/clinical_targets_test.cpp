// solver.scope and the [clinical] targets of a case config: their defaults (the default
// ranking), every key read, and each bad value rejected with one line naming the key.
#include "config/clinical_targets.h"

#include <gtest/gtest.h>

#include <fstream>

#include "base/user_error.h"
#include "config/case_config.h"
#include "test_common.h"

namespace occlude::test {
namespace {

using app::CaseConfig;
using app::ClinicalTargets;

CaseConfig Parse(const std::string& text) {
  return app::ParseCaseConfig("[synthetic]\ntriangles = 6000\n" + text, "/tmp/clinical.toml");
}

std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const app::UserError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ClinicalTargetsTest, DefaultsAreLocalScopeAndTheDefaultRanking) {
  const CaseConfig c = Parse("");
  EXPECT_EQ(c.solver.scope, "local");
  const ClinicalTargets& t = c.clinical;
  EXPECT_FALSE(t.from_config);
  EXPECT_EQ(t.mode, ClinicalTargets::Mode::kRank);
  for (int side = 0; side < 2; ++side) {
    EXPECT_EQ(t.molar_class[static_cast<std::size_t>(side)], "I");
    EXPECT_EQ(t.canine_class[static_cast<std::size_t>(side)], "I");
  }
  ASSERT_TRUE(t.overjet_mm && t.overbite_mm && t.midline_max_mm);
  EXPECT_EQ(t.overjet_mm->min, 1.0);
  EXPECT_EQ(t.overbite_mm->max, 3.0);
  EXPECT_EQ(*t.midline_max_mm, 2.0);
}

TEST(ClinicalTargetsTest, ReadsScopeAndEveryTargetKey) {
  const CaseConfig c = Parse(
      "[solver]\nscope = \"global\"\n[clinical]\nmolar_class_right = \"II\"\n"
      "molar_class_left = \"I\"\ncanine_class = \"III\"\noverjet_mm = [0.5, 2.5]\n"
      "midline_max_mm = 1\nmode = \"constraint\"\n");
  EXPECT_EQ(c.solver.scope, "global");
  const ClinicalTargets& t = c.clinical;
  EXPECT_TRUE(t.from_config);
  EXPECT_EQ(t.mode, ClinicalTargets::Mode::kConstraint);
  EXPECT_EQ(t.molar_class[0], "II");
  EXPECT_EQ(t.molar_class[1], "I");
  EXPECT_EQ(t.canine_class[0], "III");
  EXPECT_EQ(t.canine_class[1], "III");
  ASSERT_TRUE(t.overjet_mm);
  EXPECT_EQ(t.overjet_mm->min, 0.5);
  EXPECT_EQ(t.overjet_mm->max, 2.5);
  EXPECT_FALSE(t.overbite_mm) << "only the table's keys are targets";
  EXPECT_EQ(t.midline_max_mm, 1.0);
}

TEST(ClinicalTargetsTest, BadValuesNameTheKey) {
  const struct {
    const char* text;
    const char* key;
    const char* fix;
  } cases[] = {
      {"[solver]\nscope = \"everywhere\"\n", "solver.scope", "\"local\" or \"global\""},
      {"[clinical]\nmolar_class = \"IV\"\n", "clinical.molar_class", "\"I\", \"II\" or \"III\""},
      {"[clinical]\ncanine_class_left = \"1\"\n", "clinical.canine_class_left", "\"III\""},
      {"[clinical]\nmolar_class = \"I\"\nmolar_class_left = \"II\"\n", "clinical.molar_class",
       "either"},
      {"[clinical]\noverjet_mm = [3, 1]\n", "clinical.overjet_mm", "empty interval"},
      {"[clinical]\noverbite_mm = [1]\n", "clinical.overbite_mm", "[min, max]"},
      {"[clinical]\nmidline_max_mm = -1\n", "clinical.midline_max_mm", "[0, 20]"},
      {"[clinical]\nmode = \"hard\"\n", "clinical.mode", "\"rank\" or \"constraint\""},
      {"[clinical]\nmolar = \"I\"\n", "clinical.molar", "unknown key"},
  };
  for (const auto& c : cases) {
    const std::string e = ErrorOf(c.text);
    EXPECT_NE(e.find(c.key), std::string::npos) << c.text << " -> " << e;
    EXPECT_NE(e.find(c.fix), std::string::npos) << c.text << " -> " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

std::string LoadError(const std::filesystem::path& file) {
  try {
    app::LoadClinicalTargets(file);
  } catch (const app::UserError& e) {
    return e.what();
  }
  return "(no error)";
}

// `validate --global --clinical FILE`: the [clinical] table of a file with only that table or
// of a whole case config; a file without one, a missing file and a bad key are one line naming
// the file (and the key).
TEST(ClinicalTargetsTest, LoadsTheClinicalTableOfAFile) {
  TempDir tmp;
  std::ofstream(tmp / "targets.toml") << "[clinical]\nmolar_class = \"I\"\nmode = \"constraint\"\n";
  const ClinicalTargets only = app::LoadClinicalTargets(tmp / "targets.toml");
  EXPECT_TRUE(only.from_config);
  EXPECT_EQ(only.molar_class[0], "I");
  EXPECT_EQ(only.molar_class[1], "I");
  EXPECT_FALSE(only.canine_class[0]);
  EXPECT_FALSE(only.overjet_mm);
  EXPECT_EQ(only.mode, ClinicalTargets::Mode::kConstraint);

  std::ofstream(tmp / "case.toml") << "[synthetic]\ntriangles = 6000\n[clinical]\n"
                                      "canine_class_left = \"II\"\n";
  const ClinicalTargets from_case = app::LoadClinicalTargets(tmp / "case.toml");
  EXPECT_FALSE(from_case.molar_class[0]);
  EXPECT_EQ(from_case.canine_class[1], "II");

  std::ofstream(tmp / "none.toml") << "[synthetic]\ntriangles = 6000\n";
  std::ofstream(tmp / "bad.toml") << "[clinical]\nmolar_class = \"IV\"\n";
  std::ofstream(tmp / "broken.toml") << "[clinical\n";
  const struct {
    std::filesystem::path file;
    const char* says;
  } cases[] = {{tmp / "none.toml", "no [clinical] table"},
               {tmp / "missing.toml", "no such config file"},
               {tmp / "bad.toml", "clinical.molar_class"},
               {tmp / "broken.toml", "not valid TOML"}};
  for (const auto& c : cases) {
    const std::string e = LoadError(c.file);
    EXPECT_NE(e.find(c.file.filename().string()), std::string::npos) << e;
    EXPECT_NE(e.find(c.says), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace occlude::test
