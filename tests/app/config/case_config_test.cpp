// Case config files: every key read with its default, relative paths resolved
// against the file's folder, the example configs valid, and every kind of bad
// input rejected with one line naming the file, the key (with its table path)
// and the fix, unknown keys with the closest valid key.
#include "config/case_config.h"

#include <gtest/gtest.h>

#include <fstream>

#include "base/user_error.h"
#include "occlude/io/mesh_io.h"
#include "test_common.h"

namespace occlude::test {
namespace {

using app::CaseConfig;

std::filesystem::path ExamplesDir() {
  return std::filesystem::path(OCCLUDE_SOURCE_DIR) / "examples";
}

// A temporary folder with meshes/lower.stl, meshes/upper.stl and meshes/Tooth_14.stl.
class CaseConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::create_directories(tmp_ / "meshes");
    const io::TriangleMesh box = MakeBox(Eigen::Vector3d::Zero(), Eigen::Vector3d(10, 10, 10));
    for (const char* name : {"lower.stl", "upper.stl", "Tooth_14.stl", "Tooth_UpperJaw.stl"}) {
      io::WriteBinaryStl(box, tmp_ / "meshes" / name);
    }
  }
  // Writes `text` as <tmp>/<rel> and loads it.
  CaseConfig Load(const std::string& text, const std::string& rel = "case.toml") {
    const auto file = tmp_ / rel;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << text;
    return app::LoadCaseConfig(file);
  }
  std::string ErrorOf(const std::string& text) {
    try {
      Load(text);
    } catch (const app::UserError& e) {
      return e.what();
    }
    return "(no error)";
  }
  TempDir tmp_;
};

const std::string kFiles =
    "[lower]\nfile = \"meshes/lower.stl\"\n[upper]\nfile = \"meshes/upper.stl\"\n";

TEST_F(CaseConfigTest, DefaultsWithOnlyTheMeshes) {
  const CaseConfig c = Load(kFiles);
  EXPECT_EQ(c.name, "case");
  ASSERT_TRUE(c.lower && c.upper);
  EXPECT_EQ(c.lower->files.at(0), (tmp_.path() / "meshes" / "lower.stl").lexically_normal());
  EXPECT_FALSE(c.lower->parts);
  EXPECT_DOUBLE_EQ(c.contact_band_mm, 0.1);
  EXPECT_DOUBLE_EQ(c.max_penetration_mm, 0.05);
  EXPECT_DOUBLE_EQ(c.VoxelSizeMm(), 0.2);  // from the default accuracy 0.01 mm
  EXPECT_FALSE(c.up_axis_L.has_value());
  EXPECT_FALSE(c.output_dir.has_value());
  EXPECT_FALSE(c.start.matrix.has_value());
  for (bool locked : c.locked) EXPECT_FALSE(locked);
  EXPECT_FALSE(c.memory_budget_mb.has_value());
  EXPECT_TRUE(c.region_of_interest);
}

TEST_F(CaseConfigTest, RefineHoldsTheAdjustedByDefaultNoneOrAList) {
  EXPECT_TRUE(Load(kFiles).refine.hold_adjusted);
  const CaseConfig none = Load(kFiles + "[refine]\nhold = \"none\"\n");
  EXPECT_FALSE(none.refine.hold_adjusted);
  EXPECT_EQ(none.refine.hold, (std::array<bool, app::kNumDofs>{}));
  const CaseConfig list = Load(kFiles + "[refine]\nhold = [\"tx\", \"rz\"]\n");
  EXPECT_FALSE(list.refine.hold_adjusted);
  EXPECT_EQ(list.refine.hold,
            (std::array<bool, app::kNumDofs>{true, false, false, false, false, true}));
  EXPECT_TRUE(Load(kFiles + "[refine]\nhold = \"adjusted\"\n").refine.hold_adjusted);
}

TEST_F(CaseConfigTest, RegionOfInterestCanBeTurnedOff) {
  EXPECT_FALSE(Load(kFiles + "[accuracy]\nregion_of_interest = false\n").region_of_interest);
  EXPECT_TRUE(Load(kFiles + "[accuracy]\nregion_of_interest = true\n").region_of_interest);
}

TEST_F(CaseConfigTest, EveryKeyIsRead) {
  const CaseConfig c = Load(R"(
[case]
name = "patient 7"
units = "cm"
up_axis = "-z"
[lower]
parts = ["meshes/Tooth_14.stl"]
[upper]
file = "meshes/upper.stl"
[accuracy]
accuracy_mm = 0.04
voxel_mm = 0.25
sample_spacing_mm = 0.2
[contact]
band_mm = 0.2
max_penetration_mm = 0.0
[solver]
name = "nlopt-cobyla"
starts = 7
seed = 42
threads = 2
proposals = 5
max_seconds = 12.5
[solver.options]
ftol_rel = 1e-6
local = "ceres"
polish = true
evaluations = 500
[bounds]
tx_mm = [-1, 2]
rz_deg = [-4.5, 0]
locked = ["rx", "ry"]
[start]
translation_mm = [0.5, -1, 0]
rotation_deg = [0, 2, 0]
pivot_mm = [1, 2, 3]
[adjust]
translation_mm = [0, 0.1, 0]
rotation_deg = [0.5, 0, 0]
[output]
folder = "results/p7"
[report]
map_max_mm = 0.8
map_penetration_from_mm = 0.02
image_width_px = 800
[limits]
memory_budget_mb = 1500
)");
  EXPECT_EQ(c.name, "patient 7");
  EXPECT_EQ(c.units, io::LengthUnit::kCentimetre);
  EXPECT_EQ(*c.up_axis_L, Eigen::Vector3d(0, 0, -1));
  EXPECT_TRUE(c.lower->parts);
  EXPECT_DOUBLE_EQ(c.VoxelSizeMm(), 0.25);
  EXPECT_DOUBLE_EQ(c.sample_spacing_mm, 0.2);
  EXPECT_DOUBLE_EQ(c.contact_band_mm, 0.2);
  EXPECT_DOUBLE_EQ(c.max_penetration_mm, 0.0);
  EXPECT_EQ(c.solver.name, "nlopt-cobyla");
  EXPECT_EQ(c.solver.starts, 7);
  EXPECT_EQ(c.solver.seed, 42u);
  EXPECT_EQ(c.solver.threads, 2);
  EXPECT_EQ(c.solver.proposals, 5);
  EXPECT_DOUBLE_EQ(c.solver.max_seconds, 12.5);
  EXPECT_DOUBLE_EQ(std::get<double>(c.solver.options.at("ftol_rel")), 1e-6);
  EXPECT_EQ(std::get<std::string>(c.solver.options.at("local")), "ceres");
  EXPECT_TRUE(std::get<bool>(c.solver.options.at("polish")));
  EXPECT_EQ(std::get<std::int64_t>(c.solver.options.at("evaluations")), 500);
  EXPECT_DOUBLE_EQ(c.bounds[0].min, -1.0);
  EXPECT_DOUBLE_EQ(c.bounds[0].max, 2.0);
  EXPECT_DOUBLE_EQ(c.bounds[5].min, -4.5);
  EXPECT_TRUE(c.locked[3] && c.locked[4]);
  EXPECT_FALSE(c.locked[0] || c.locked[5]);
  EXPECT_EQ(c.start.params.translation_mm, Eigen::Vector3d(0.5, -1, 0));
  EXPECT_EQ(*c.start.pivot_mm, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(c.adjust.rotation_deg, Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(*c.output_dir, (tmp_.path() / "results" / "p7").lexically_normal());
  EXPECT_DOUBLE_EQ(c.report.map_max_mm, 0.8);
  EXPECT_EQ(c.report.image_width_px, 800);
  EXPECT_DOUBLE_EQ(*c.memory_budget_mb, 1500.0);
}

TEST_F(CaseConfigTest, RelativePathsResolveAgainstTheConfigFolder) {
  const CaseConfig c = Load(
      "[lower]\nfile = \"../meshes/lower.stl\"\n[upper]\nparts = [\"../meshes/Tooth_14.stl\", "
      "\"../meshes/Tooth_UpperJaw.stl\"]\n[output]\nfolder = \"../out\"\n",
      "configs/case.toml");
  EXPECT_EQ(c.lower->files.at(0), (tmp_.path() / "meshes" / "lower.stl").lexically_normal());
  ASSERT_EQ(c.upper->files.size(), 2u);
  EXPECT_EQ(c.upper->files[1], (tmp_.path() / "meshes" / "Tooth_UpperJaw.stl").lexically_normal());
  EXPECT_EQ(*c.output_dir, (tmp_.path() / "out").lexically_normal());
}

TEST_F(CaseConfigTest, StartPoseFromMatrixOrParameters) {
  const CaseConfig m =
      Load(kFiles + "[start]\nmatrix = [[0,-1,0,1],[1,0,0,2],[0,0,1,3],[0,0,0,1]]\n");
  const Eigen::Isometry3d X = app::StartPoseOf(m, Eigen::Vector3d(5, 5, 5));
  EXPECT_NEAR(X.translation().y(), 2.0, kExactMm);
  EXPECT_NEAR(X.linear()(1, 0), 1.0, kExactMm);
  const CaseConfig p = Load(kFiles + "[start]\ntranslation_mm = [0, -0.2, 0]\n");
  EXPECT_TRUE(app::StartPoseOf(p, Eigen::Vector3d(5, 5, 5))
                  .translation()
                  .isApprox(Eigen::Vector3d(0, -0.2, 0)));
}

TEST_F(CaseConfigTest, SyntheticSource) {
  const CaseConfig c = Load("[synthetic]\ntriangles = 6000\nseed = 4\n");
  ASSERT_TRUE(c.synthetic.has_value());
  EXPECT_EQ(c.synthetic->triangles, 6000u);
  EXPECT_EQ(c.synthetic->seed, 4u);
  EXPECT_FALSE(c.lower.has_value());
}

TEST_F(CaseConfigTest, LandmarksFileIsRelativeToTheConfigAndMustExist) {
  EXPECT_FALSE(Load(kFiles).landmarks_file.has_value());
  std::ofstream(tmp_ / "meshes" / "landmarks.csv") << "jaw,tooth,type,x_mm,y_mm,z_mm\n";
  const CaseConfig c = Load(kFiles + "[landmarks]\nfile = \"meshes/landmarks.csv\"\n");
  ASSERT_TRUE(c.landmarks_file.has_value());
  EXPECT_EQ(*c.landmarks_file, (tmp_.path() / "meshes" / "landmarks.csv").lexically_normal());
  const std::string missing = ErrorOf(kFiles + "[landmarks]\nfile = \"nothere.csv\"\n");
  EXPECT_NE(missing.find("landmarks.file"), std::string::npos) << missing;
  EXPECT_NE(missing.find("no such file"), std::string::npos) << missing;
  const std::string misspelt = ErrorOf(kFiles + "[landmarks]\nfiles = \"x.csv\"\n");
  EXPECT_NE(misspelt.find("landmarks.files"), std::string::npos) << misspelt;
  EXPECT_NE(misspelt.find("file"), std::string::npos) << misspelt;
}

TEST(CaseConfigEditDistance, Levenshtein) {
  EXPECT_EQ(app::EditDistance("band", "band_mm"), 3u);
  EXPECT_EQ(app::EditDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(app::EditDistance("", "abc"), 3u);
  EXPECT_EQ(app::EditDistance("same", "same"), 0u);
}

TEST(CaseConfigExamples, EveryExampleLoads) {
  const bool have_data =
      SharedCase("a-bite-3shape").has_value() && SharedCase("b-open-3shape").has_value();
  for (const char* name : {"synthetic.toml", "a-bite-3shape.toml", "a-bite-3shape-teeth.toml",
                           "b-open-3shape.toml", "c1-ios.toml"}) {
    if (std::string(name) != "synthetic.toml" && !have_data) continue;
    SCOPED_TRACE(name);
    const CaseConfig c = app::LoadCaseConfig(ExamplesDir() / name);
    ASSERT_TRUE(c.output_dir.has_value());
    EXPECT_EQ(c.output_dir->parent_path().filename(), "out");
  }
  if (have_data) {  // the per-tooth example names files of the shared data folder
    const CaseConfig teeth = app::LoadCaseConfig(ExamplesDir() / "a-bite-3shape-teeth.toml");
    EXPECT_EQ(teeth.upper->files.size(), 15u);
  }
}

struct BadConfig {
  const char* name;
  std::string text;
  std::vector<std::string> expected;  // substrings of the one-line message
};

void PrintTo(const BadConfig& c, std::ostream* os) { *os << c.name; }  // not its bytes

class CaseConfigBadTest : public CaseConfigTest, public ::testing::WithParamInterface<BadConfig> {};

TEST_P(CaseConfigBadTest, OneLineErrorNamingTheKey) {
  const std::string message = ErrorOf(GetParam().text);
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(message.find("case.toml"), std::string::npos) << message;
  for (const auto& e : GetParam().expected)
    EXPECT_NE(message.find(e), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CaseConfigBadTest,
    ::testing::Values(
        BadConfig{"unknown_key",
                  kFiles + "[contact]\nband = 0.1\n",
                  {"contact.band: unknown key", "did you mean 'contact.band_mm'"}},
        BadConfig{"unknown_key_at_root",
                  "band_mm = 0.1\n" + kFiles,
                  {"band_mm: unknown key", "'contact.band_mm'"}},
        BadConfig{"unknown_table",
                  kFiles + "[contacts]\nband_mm = 0.1\n",
                  {"contacts: unknown key", "'contact'"}},
        BadConfig{"unknown_solver_key",
                  kFiles + "[solver]\nstart = 3\n",
                  {"solver.start", "'solver.starts'"}},
        BadConfig{"wrong_type",
                  kFiles + "[contact]\nband_mm = \"wide\"\n",
                  {"contact.band_mm: must be a band in mm in (0, 5]", "got a string"}},
        BadConfig{"table_expected", "contact = 3\n" + kFiles, {"contact: must be a table"}},
        BadConfig{"integer_expected",
                  kFiles + "[solver]\nstarts = 2.5\n",
                  {"solver.starts: must be an integer"}},
        BadConfig{"zero_voxel",
                  kFiles + "[accuracy]\nvoxel_mm = 0\n",
                  {"accuracy.voxel_mm", "positive", "got 0"}},
        BadConfig{"negative_voxel",
                  kFiles + "[accuracy]\nvoxel_mm = -0.2\n",
                  {"accuracy.voxel_mm", "positive"}},
        BadConfig{"band_over_5mm",
                  kFiles + "[contact]\nband_mm = 6\n",
                  {"contact.band_mm", "(0, 5]", "got 6"}},
        BadConfig{"zero_band", kFiles + "[contact]\nband_mm = 0\n", {"contact.band_mm", "(0, 5]"}},
        BadConfig{"negative_penetration",
                  kFiles + "[contact]\nmax_penetration_mm = -0.1\n",
                  {"contact.max_penetration_mm", "[0, 5]"}},
        BadConfig{"min_over_max",
                  kFiles + "[bounds]\ntx_mm = [2, -2]\n",
                  {"bounds.tx_mm", "min 2 is greater than max -2"}},
        BadConfig{"bounds_not_a_pair",
                  kFiles + "[bounds]\nrx_deg = [1]\n",
                  {"bounds.rx_deg", "[min, max]"}},
        BadConfig{"all_locked",
                  kFiles + "[bounds]\nlocked = [\"tx\",\"ty\",\"tz\",\"rx\",\"ry\",\"rz\"]\n",
                  {"bounds.locked", "all six", "leave at least one free"}},
        BadConfig{"unknown_dof",
                  kFiles + "[bounds]\nlocked = [\"rzz\"]\n",
                  {"bounds.locked", "'rzz'", "'rz'"}},
        BadConfig{"hold_word",
                  kFiles + "[refine]\nhold = \"all\"\n",
                  {"refine.hold", "\"adjusted\"", "\"none\""}},
        BadConfig{"hold_dof",
                  kFiles + "[refine]\nhold = [\"tz\", \"rxx\"]\n",
                  {"refine.hold", "'rxx'", "'rx'"}},
        BadConfig{"missing_mesh",
                  "[lower]\nfile = \"meshes/nope.stl\"\n[upper]\nfile = \"meshes/upper.stl\"\n",
                  {"lower.file: no such file", "meshes/nope.stl"}},
        BadConfig{"missing_part",
                  "[lower]\nfile = \"meshes/lower.stl\"\n[upper]\nparts = "
                  "[\"meshes/Tooth_14.stl\", \"meshes/Tooth_9.stl\"]\n",
                  {"upper.parts[1]: no such file", "Tooth_9.stl"}},
        BadConfig{"folder_as_mesh",
                  "[lower]\nfile = \"meshes\"\n[upper]\nfile = \"meshes/upper.stl\"\n",
                  {"lower.file", "is not a file"}},
        BadConfig{"file_and_parts",
                  "[lower]\nfile = \"meshes/lower.stl\"\nparts = "
                  "[\"meshes/lower.stl\"]\n[upper]\nfile = \"meshes/upper.stl\"\n",
                  {"[lower]", "exactly one of file"}},
        BadConfig{"no_meshes", "[contact]\nband_mm = 0.1\n", {"lower: missing", "[synthetic]"}},
        BadConfig{"synthetic_and_files",
                  kFiles + "[synthetic]\ntriangles = 5000\n",
                  {"synthetic", "not both"}},
        BadConfig{"synthetic_budget",
                  "[synthetic]\ntriangles = 10\n",
                  {"synthetic.triangles", "[5000, 500000]"}},
        BadConfig{"non_rigid_matrix",
                  kFiles + "[start]\nmatrix = [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\n",
                  {"start.matrix", "not orthonormal"}},
        BadConfig{"nan_matrix",
                  kFiles + "[start]\nmatrix = [[nan,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\n",
                  {"start.matrix", "NaN"}},
        BadConfig{"matrix_not_4x4",
                  kFiles + "[start]\nmatrix = [[1,0,0],[0,1,0],[0,0,1]]\n",
                  {"start.matrix", "4x4"}},
        BadConfig{"matrix_and_translation",
                  kFiles + "[start]\ntranslation_mm = [0,0,0]\nmatrix = "
                           "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]\n",
                  {"start.matrix", "not both"}},
        BadConfig{"translation_not_3",
                  kFiles + "[start]\ntranslation_mm = [0, 1]\n",
                  {"start.translation_mm", "[x, y, z]"}},
        BadConfig{"bad_units",
                  kFiles + "[case]\nunits = \"furlong\"\n",
                  {"case.units", "furlong", "mm, cm"}},
        BadConfig{
            "bad_up_axis", kFiles + "[case]\nup_axis = \"w\"\n", {"case.up_axis", "not an axis"}},
        BadConfig{"region_of_interest_not_bool",
                  kFiles + "[accuracy]\nregion_of_interest = 1\n",
                  {"accuracy.region_of_interest", "true or false"}},
        BadConfig{"region_of_interest_misspelt",
                  kFiles + "[accuracy]\nregion_of_intrest = false\n",
                  {"accuracy.region_of_intrest: unknown key", "'accuracy.region_of_interest'"}},
        BadConfig{"memory_budget_not_positive",
                  kFiles + "[limits]\nmemory_budget_mb = 0\n",
                  {"limits.memory_budget_mb", "positive number of megabytes"}},
        BadConfig{"unknown_limit",
                  kFiles + "[limits]\nmemory_mb = 10\n",
                  {"limits.memory_mb: unknown key", "'limits.memory_budget_mb'"}},
        // Regressions found by fuzz_case_config: messages quoting the file stay one line.
        BadConfig{"newline_in_toml_error",
                  kFiles + "[case]\nname = t\n",
                  {"not valid TOML", "saw 't\\n'"}},
        BadConfig{"newline_in_key", kFiles + "\"a\\nb\" = 1\n", {"a\\nb: unknown key"}},
        BadConfig{
            "newline_in_value", kFiles + "[case]\nunits = \"m\\nm\"\n", {"unknown unit 'm\\nm'"}},
        BadConfig{"syntax_error", kFiles + "[contact\nband_mm = 0.1\n", {"not valid TOML"}},
        BadConfig{"map_scale_below_band",
                  kFiles + "[contact]\nband_mm = 1\n[report]\nmap_max_mm = 0.5\n",
                  {"map_max_mm", "contact.band_mm"}}),
    [](const ::testing::TestParamInfo<BadConfig>& param_info) {
      return std::string(param_info.param.name);
    });

TEST(CaseConfigFile, MissingOrFolder) {
  TempDir tmp;
  EXPECT_THROW(app::LoadCaseConfig(tmp / "nope.toml"), app::UserError);
  EXPECT_THROW(app::LoadCaseConfig(tmp.path()), app::UserError);
}

}  // namespace
}  // namespace occlude::test
