// Odd but valid inputs (README, "Reliability") through the real commands: each runs to the
// end (exit 0, the command's outputs written), with a warning where it helps
// the user: a single triangle; jaws in metres (a warning naming units = "m",
// and none once the unit is given); jaws 200 mm apart (they may not share a
// frame); the same surface for both jaws.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "input_suite.h"
#include "occlude/io/mesh_io.h"

namespace occlude::test::suite {
namespace {

struct OddInput {
  const char* name;
  std::vector<std::string> commands;  ///< where it runs
  std::function<void(const CommandForm&, Inputs*)> make;
  std::string warning;     ///< an "occlude: warning:" line must contain this ("" = none needed)
  std::string no_warning;  ///< no warning line may contain this ("" = not checked)
};

io::TriangleMesh Good(const char* jaw) {
  return io::LoadMesh(GoodCase() / (std::string(jaw) + ".stl"));
}

fs::path Write(const io::TriangleMesh& mesh, const fs::path& file) {
  io::WriteBinaryStl(mesh, file);
  return file;
}

io::TriangleMesh InMetres(io::TriangleMesh mesh) {
  for (auto& v : mesh.vertices) v *= 1e-3;
  return mesh;
}

void MetreFiles(Inputs* in) {
  in->lower = Write(InMetres(Good("lower")), in->dir / "lower-m.stl");
  in->upper = Write(InMetres(Good("upper")), in->dir / "upper-m.stl");
}

std::vector<OddInput> OddInputs() {
  return {
      {"single_triangle",
       {"collide", "report"},
       [](const CommandForm&, Inputs* in) {
         // One triangle of the lower box's top face, under the upper box.
         io::TriangleMesh one = Good("lower");
         std::size_t top = 0;
         while (top + 1 < one.num_triangles() && one.face_normals[top].y() < 0.5) ++top;
         one.triangles = {one.triangles[top]};
         one.triangle_part = {0};
         one.ComputeFaceNormals();
         in->lower = Write(one, in->dir / "one.stl");
       },
       "",
       ""},
      {"jaws_in_metres",
       {"collide", "report"},
       [](const CommandForm&, Inputs* in) { MetreFiles(in); },
       "set units = \"m\"",
       ""},
      {"jaws_in_metres_with_the_unit",
       {"collide", "report"},
       [](const CommandForm& form, Inputs* in) {
         MetreFiles(in);
         if (std::string(form.name) == "collide") {
           in->extra = "--units m";
         } else {
           in->config += "[case]\nunits = \"m\"\n";
         }
       },
       "",
       "units"},
      {"jaws_200mm_apart",
       {"collide", "report"},
       [](const CommandForm&, Inputs* in) {
         const Eigen::Isometry3d apart(Eigen::Translation3d(200, 0, 0));
         in->upper = Write(Good("upper").Transformed(apart), in->dir / "upper-apart.stl");
       },
       "may not share a frame",
       ""},
      {"identical_jaws",
       {"collide", "report"},
       [](const CommandForm&, Inputs* in) { in->upper = in->lower; },
       "the upper and lower jaws are the same surface",
       ""},
  };
}

struct OddRun {
  CommandForm command;
  OddInput input;
};

void PrintTo(const OddRun& run, std::ostream* os) {
  *os << run.command.name << " / " << run.input.name;
}

std::vector<OddRun> AllOddRuns() {
  std::vector<OddRun> runs;
  for (const CommandForm& command : Commands()) {
    for (const OddInput& input : OddInputs()) {
      for (const std::string& name : input.commands) {
        if (name == command.name) runs.push_back({command, input});
      }
    }
  }
  return runs;
}

// The file every successful run of the command writes.
const char* OutputOf(const CommandForm& form) {
  return std::string(form.name) == "collide" ? "collide.json" : "report.html";
}

class OddInputTest : public ::testing::TestWithParam<OddRun> {};

TEST_P(OddInputTest, RunsToTheEndWithTheHelpfulWarning) {
  const OddRun& run = GetParam();
  TempDir tmp;
  Inputs in = GoodInputs(tmp.path());
  run.input.make(run.command, &in);
  const CommandRun r = RunPrepared(Prepare(run.command, in));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::is_regular_file(in.out / OutputOf(run.command))) << r.output;
  std::vector<std::string> warnings;
  for (const std::string& line : Lines(r.output)) {
    if (line.rfind("occlude: warning: ", 0) == 0) warnings.push_back(line);
  }
  if (!run.input.warning.empty()) {
    bool found = false;
    for (const std::string& w : warnings)
      found = found || w.find(run.input.warning) != std::string::npos;
    EXPECT_TRUE(found) << "no warning with '" << run.input.warning << "':\n" << r.output;
  }
  if (!run.input.no_warning.empty()) {
    for (const std::string& w : warnings)
      EXPECT_EQ(w.find(run.input.no_warning), std::string::npos) << w;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, OddInputTest, ::testing::ValuesIn(AllOddRuns()),
                         [](const ::testing::TestParamInfo<OddRun>& param_info) {
                           return NamePart(std::string(param_info.param.command.name) + "_" +
                                           param_info.param.input.name);
                         });

}  // namespace
}  // namespace occlude::test::suite
