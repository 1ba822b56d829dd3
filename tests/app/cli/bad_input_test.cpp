// The bad-input suite (README, "Reliability") through the real commands: every bad mesh,
// config, pose file and output folder, run through every command that reads
// that kind of input (input_suite.h lists the commands), must give exactly one
// error line ("occlude: error: ...", the last line of the output) that names
// the file or key and what is wrong, a non-zero exit, and no file written
// anywhere in the run's folder (a failed run may leave an empty output folder).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <regex>

#include "input_suite.h"

namespace occlude::test::suite {
namespace {

struct BadInput {
  const char* name;
  Reads kind;  ///< kMeshes, kConfig, kPose or kOut
  std::function<void(const CommandForm&, Inputs*)> make;
  std::string expected;                                  ///< in the error line
  std::map<std::string, std::string> expected_for = {};  ///< per command, instead
};

// --- bad meshes (they replace the lower jaw) ---------------------------------

void BadLower(Inputs* in, const std::string& name, const std::string& bytes) {
  in->lower = in->dir / name;
  std::ofstream(in->lower, std::ios::binary) << bytes;
}

std::string BoxBytes(const Inputs& in) { return WriteBox(in.dir / "box-source.stl"); }

std::string WithCount(std::string stl, std::uint32_t count) {
  for (int i = 0; i < 4; ++i)
    stl[80 + static_cast<std::size_t>(i)] = static_cast<char>((count >> (8 * i)) & 0xff);
  return stl;
}

// A one-facet ASCII STL whose second vertex line is `vertex`.
std::string AsciiFacet(const std::string& vertex) {
  return "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   " + vertex +
         "\n   vertex 0 10 0\n  endloop\n endfacet\nendsolid t\n";
}

// Binary STL of the given triangles (9 floats each).
std::string BinaryStl(const std::vector<std::array<float, 9>>& triangles) {
  std::string stl(80, ' ');
  stl +=
      WithCount(std::string(84, '\0'), static_cast<std::uint32_t>(triangles.size())).substr(80, 4);
  for (const auto& t : triangles) {
    stl += std::string(12, '\0');  // normal (ignored)
    for (const float f : t) stl.append(reinterpret_cast<const char*>(&f), 4);
    stl += std::string(2, '\0');
  }
  return stl;
}

std::vector<BadInput> MeshInputs() {
  return {
      {"empty_file", kMeshes, [](const CommandForm&, Inputs* in) { BadLower(in, "empty.stl", ""); },
       "the file is empty (0 bytes)"},
      {"folder_as_mesh",
       kMeshes,
       [](const CommandForm&, Inputs* in) {
         in->lower = in->dir / "folder.stl";
         fs::create_directory(in->lower);
       },
       "is a folder",
       {{"report", "lower.file: '"}}},
      {"missing_file",
       kMeshes,
       [](const CommandForm&, Inputs* in) { in->lower = in->dir / "nope.stl"; },
       "no such file",
       {{"report", "lower.file: no such file"}, {"bench", "not found"}}},
      {"unreadable_file", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "secret.stl", BoxBytes(*in));
         fs::permissions(in->lower, fs::perms::none);
         in->unprivileged = true;
       },
       "cannot open for reading: Permission denied; check the file's permissions"},
      {"truncated_binary_stl", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "cut.stl", BoxBytes(*in).substr(0, 664));
       },
       "needs 684 bytes, but the file has 664 bytes; the file is truncated"},
      {"huge_claimed_count", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "huge.stl", WithCount(BoxBytes(*in), 4000000000u));
       },
       "header says 4000000000 triangles, which needs 200000000084 bytes, but the file has 684 "
       "bytes"},
      {"ascii_stl_nan", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "nan.stl", AsciiFacet("vertex 10 nan 0"));
       },
       "line 5: non-finite vertex coordinate 'nan'"},
      {"ascii_stl_inf", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "inf.stl", AsciiFacet("vertex -inf 0 0"));
       },
       "line 5: non-finite vertex coordinate '-inf'"},
      {"ascii_stl_garbage", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "abc.stl", AsciiFacet("vertex 10 abc 0"));
       },
       "line 5: 'abc' is not a number"},
      {"ascii_stl_missing_endloop", kMeshes,
       [](const CommandForm&, Inputs* in) {
         std::string text = AsciiFacet("vertex 10 0 0");
         text.erase(text.find("  endloop\n"), 10);
         BadLower(in, "endloop.stl", text);
       },
       "line 7: expected 'endloop' in facet 1, found 'endfacet'"},
      {"obj_index_out_of_range", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "range.obj", "v 0 0 0\nv 10 0 0\nv 0 10 0\nf 1 2 7\n");
       },
       "line 4: a face refers to vertex 7 but the file has only 3 vertices"},
      {"only_degenerate_triangles", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "flat.stl",
                  BinaryStl({{0, 0, 0, 1, 1, 1, 2, 2, 2}, {0, 0, 0, 0, 0, 0, 5, 5, 5}}));
       },
       "all 2 triangles are degenerate (zero area)"},
      // Two small triangles 10 km apart: little memory, but no grid at 0.8 mm spans them.
      {"grid_overflow", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "far.stl",
                  BinaryStl(
                      {{0, 0, 0, 10, 0, 0, 0, 10, 0}, {1e7f, 0, 0, 1e7f + 10, 0, 0, 1e7f, 10, 0}}));
       },
       "voxel grid too large: the mesh spans 1e+07 mm"},
      // Coordinates of 10^12 mm: no voxel size the commands accept can hold the grid.
      {"huge_coordinates", kMeshes,
       [](const CommandForm&, Inputs* in) {
         BadLower(in, "huge-coordinates.stl", BinaryStl({{0, 0, 0, 1e12f, 0, 0, 0, 1e12f, 0}}));
       },
       "the mesh spans 1e+12 mm, too large for a voxel grid"},
  };
}

// --- bad configs --------------------------------------------------------------

void Append(Inputs* in, const std::string& text) { in->config += text; }

std::vector<BadInput> ConfigInputs() {
  return {
      {"unknown_key", kConfig,
       [](const CommandForm&, Inputs* in) { Append(in, "[contact]\nbnd_mm = 0.1\n"); },
       ":8: contact.bnd_mm: unknown key; did you mean 'contact.band_mm'?"},
      {"wrong_type", kConfig,
       [](const CommandForm&, Inputs* in) { Append(in, "[contact]\nband_mm = \"wide\"\n"); },
       "contact.band_mm: must be a band in mm in (0, 5], got a string"},
      {"zero_voxel", kConfig,
       [](const CommandForm&, Inputs* in) { Replace(&in->config, "0.8", "0"); },
       "accuracy.voxel_mm: must be a positive voxel size in mm, at most 5, got 0"},
      {"negative_voxel", kConfig,
       [](const CommandForm&, Inputs* in) { Replace(&in->config, "0.8", "-0.2"); },
       "accuracy.voxel_mm: must be a positive voxel size in mm, at most 5, got -0.2"},
      {"band_over_5mm", kConfig,
       [](const CommandForm&, Inputs* in) { Append(in, "[contact]\nband_mm = 6\n"); },
       "contact.band_mm: must be a band in mm in (0, 5], got 6"},
      {"bounds_min_over_max", kConfig,
       [](const CommandForm&, Inputs* in) { Append(in, "[bounds]\ntx_mm = [2, -2]\n"); },
       "bounds.tx_mm: min 2 is greater than max -2"},
      {"all_dofs_locked", kConfig,
       [](const CommandForm&, Inputs* in) {
         Append(in, "[bounds]\nlocked = [\"tx\", \"ty\", \"tz\", \"rx\", \"ry\", \"rz\"]\n");
       },
       "bounds.locked: all six degrees of freedom are locked; leave at least one free"},
      {"missing_mesh_path", kConfig,
       [](const CommandForm&, Inputs* in) {
         Replace(&in->config, "{lower}", (in->dir / "gone.stl").string());
       },
       "lower.file: no such file"},
      {"no_lower_jaw", kConfig,
       [](const CommandForm&, Inputs* in) {
         Replace(&in->config, "[lower]\nfile = \"{lower}\"\n", "");
       },
       "lower: missing; give [lower] and [upper]"},
      {"bad_memory_budget", kConfig,
       [](const CommandForm&, Inputs* in) { Append(in, "[limits]\nmemory_budget_mb = -5\n"); },
       "limits.memory_budget_mb: must be a positive number of megabytes"},
      {"not_toml", kConfig, [](const CommandForm&, Inputs* in) { Append(in, "[contact\n"); },
       "not valid TOML"},
      {"empty_config", kConfig, [](const CommandForm&, Inputs* in) { in->config.clear(); },
       "lower: missing"},
      {"config_is_folder", kConfig,
       [](const CommandForm&, Inputs* in) {
         in->config_file = in->dir / "folder.toml";
         in->write_config = false;
         fs::create_directory(in->config_file);
       },
       "is a folder; give the case's .toml file"},
      {"missing_config", kConfig,
       [](const CommandForm&, Inputs* in) {
         in->config_file = in->dir / "nope.toml";
         in->write_config = false;
       },
       "no such config file"},
      {"unreadable_config", kConfig,
       [](const CommandForm&, Inputs* in) {
         std::ofstream(in->config_file);
         fs::permissions(in->config_file, fs::perms::none);
         in->unprivileged = true;
       },
       "cannot read the config file: Permission denied; check the file's permissions"},
      {"output_folder_not_writable", kConfig,
       [](const CommandForm&, Inputs* in) {
         fs::create_directory(in->dir / "ro");
         fs::permissions(in->dir / "ro", fs::perms::owner_read | fs::perms::owner_exec |
                                             fs::perms::others_read | fs::perms::others_exec);
         Append(in, "[output]\nfolder = \"ro/report\"\n");
         in->out_from_config = true;
         in->unprivileged = true;
       },
       "output.folder: "},
      {"memory_budget_exceeded", kConfig,
       [](const CommandForm&, Inputs* in) { Append(in, "[limits]\nmemory_budget_mb = 1\n"); },
       "over the memory budget of 1.0 MB (limits.memory_budget_mb)"},
  };
}

// --- bad pose files, output folders and options ------------------------------------

void Pose(Inputs* in, const std::string& json) { std::ofstream(in->pose, std::ios::trunc) << json; }

std::vector<BadInput> OtherInputs() {
  return {
      {"pose_not_rigid", kPose,
       [](const CommandForm&, Inputs* in) {
         Pose(in, R"({"X_LU": [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})");
       },
       "rotation part is not orthonormal"},
      {"pose_reflection", kPose,
       [](const CommandForm&, Inputs* in) {
         Pose(in, R"({"X_LU": [[-1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})");
       },
       "rotation part is a reflection"},
      {"pose_nan", kPose,
       [](const CommandForm&, Inputs* in) {
         Pose(in, R"({"X_LU": [[NaN,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})");
       },
       "not valid JSON"},
      {"pose_overflow", kPose,
       [](const CommandForm&, Inputs* in) {
         Pose(in, R"({"X_LU": [[1e999,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})");
       },
       "not valid JSON"},
      {"pose_null_entry", kPose,
       [](const CommandForm&, Inputs* in) {
         Pose(in, R"({"X_LU": [[null,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})");
       },
       "\"X_LU\" has a non-number entry"},
      {"pose_not_4x4", kPose,
       [](const CommandForm&, Inputs* in) { Pose(in, R"({"X_LU": [[1,0,0],[0,1,0],[0,0,1]]})"); },
       "\"X_LU\" is not a 4x4 array"},
      {"pose_missing", kPose,
       [](const CommandForm&, Inputs* in) { in->pose = in->dir / "nope.json"; },
       "cannot open the pose file"},
      {"out_not_writable", kOut,
       [](const CommandForm&, Inputs* in) {
         fs::create_directory(in->out);
         fs::permissions(in->out, fs::perms::owner_read | fs::perms::owner_exec |
                                      fs::perms::others_read | fs::perms::others_exec);
         in->unprivileged = true;
       },
       "output folder is not writable; choose a writable --out"},
      {"out_is_a_file", kOut,
       [](const CommandForm&, Inputs* in) { std::ofstream(in->out) << "keep me\n"; },
       "output path exists and is not a folder"},
      {"memory_budget_exceeded_option", kOut,
       [](const CommandForm&, Inputs* in) { in->extra = "--memory-budget-mb 1"; },
       "over the memory budget of 1.0 MB (--memory-budget-mb)"},
  };
}

struct BadRun {
  CommandForm command;
  BadInput input;
};

std::vector<BadRun> AllBadRuns() {
  std::vector<BadRun> runs;
  std::vector<BadInput> inputs = MeshInputs();
  for (auto* more : {ConfigInputs, OtherInputs}) {
    for (auto& i : more()) inputs.push_back(i);
  }
  for (const CommandForm& command : Commands()) {
    for (const BadInput& input : inputs) {
      // A case folder takes meshes only as lower.stl and upper.stl.
      const bool through_folder = input.kind == kMeshes && (command.reads & kCaseFolder) != 0 &&
                                  std::string(input.name).rfind("obj_", 0) != 0;
      const bool applies = (command.reads & input.kind) != 0 || through_folder;
      if (applies) runs.push_back({command, input});
    }
  }
  return runs;
}

// What the error line must name: the spoiled file (or folder, or option).
std::string Named(const BadRun& run, const Inputs& in) {
  switch (run.input.kind) {
    case kMeshes:
      return (run.command.reads & kCaseFolder) != 0 ? "bench-case/lower.stl"
                                                    : in.lower.filename().string();
    case kConfig:
      return in.config_file.filename().string();
    case kPose:
      return in.pose.filename().string();
    default:
      return in.extra.empty() ? in.out.filename().string() : in.extra.substr(0, in.extra.find(' '));
  }
}

// For gtest's messages: the name, not the bytes.
void PrintTo(const BadRun& run, std::ostream* os) {
  *os << run.command.name << " / " << run.input.name;
}

class BadInputTest : public ::testing::TestWithParam<BadRun> {};

TEST_P(BadInputTest, OneErrorLineNamingItNonZeroExitNoFileWritten) {
  const BadRun& run = GetParam();
  TempDir tmp;
  Inputs in = GoodInputs(tmp.path());
  run.input.make(run.command, &in);
  const PreparedRun prepared = Prepare(run.command, in);
  if (!prepared.skipped.empty()) GTEST_SKIP() << prepared.skipped;
  const std::set<std::string> before = FilesBelow(tmp.path());
  const CommandRun r = RunPrepared(prepared);

  EXPECT_NE(r.exit_code, 0) << r.output;
  const auto it = run.input.expected_for.find(run.command.name);
  const std::string expected = it != run.input.expected_for.end() ? it->second : run.input.expected;
  const std::vector<std::string> lines = Lines(r.output);
  std::size_t error_lines = 0;
  for (const std::string& line : lines)
    error_lines += line.find("error") != std::string::npos ? 1 : 0;
  EXPECT_EQ(error_lines, 1u) << r.output;
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines.back().rfind("occlude: error: ", 0), 0u) << r.output;
  EXPECT_NE(lines.back().find(expected), std::string::npos) << "expected: " << expected << "\n"
                                                            << r.output;
  EXPECT_NE(lines.back().find(Named(run, in)), std::string::npos)
      << "does not name " << Named(run, in);
  // Writable again, so that the listing (and the clean-up) see everything.
  std::error_code ec;
  for (const fs::path& p : {in.out, in.dir / "ro", in.lower, in.config_file}) {
    if (fs::exists(p, ec)) fs::permissions(p, fs::perms::owner_all, fs::perm_options::add, ec);
  }
  EXPECT_EQ(FilesBelow(tmp.path()), before) << "a failed run wrote a file";
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, BadInputTest, ::testing::ValuesIn(AllBadRuns()),
                         [](const ::testing::TestParamInfo<BadRun>& param_info) {
                           return NamePart(std::string(param_info.param.command.name) + "_" +
                                           param_info.param.input.name);
                         });

// The voxel size the memory error names does fit: a rerun with it goes through.
TEST(MemoryGuardTest, TheSuggestedVoxelSizeRuns) {
  TempDir tmp;
  const std::string jaws = " --lower " + (GoodCase() / "lower.stl").string() + " --upper " +
                           (GoodCase() / "upper.stl").string() + " --memory-budget-mb 20";
  const CommandRun refused = Occlude("collide" + jaws + " --voxel 0.05");
  ASSERT_NE(refused.exit_code, 0) << refused.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(
      refused.output, m, std::regex("the smallest voxel size that fits is about ([0-9.]+) mm")))
      << refused.output;
  const double fits = std::stod(m[1]);
  EXPECT_GT(fits, 0.05);
  const CommandRun rerun = Occlude("collide" + jaws + " --voxel " + m[1].str());
  EXPECT_EQ(rerun.exit_code, 0) << rerun.output;
  // Within 10 % of the limit: the suggestion is the smallest, not any size that fits.
  std::ostringstream smaller;
  smaller << 0.9 * fits;
  EXPECT_NE(Occlude("collide" + jaws + " --voxel " + smaller.str()).exit_code, 0);
}

}  // namespace
}  // namespace occlude::test::suite
