// `occlude synth`: writes the procedural synthetic jaw pair as a case folder
// (upper.stl and lower.stl in the lower jaw's frame at the ground-truth bite,
// like the real cases, plus truth.json with the pose and the known contacts).
#include <iostream>
#include <sstream>

#include "commands.h"
#include "occlude/io/mesh_io.h"
#include "occlude/io/synthetic_jaws.h"
#include "output_files.h"
#include "synthetic_case.h"

namespace occlude::app {
namespace {

std::string TruthJson(const io::SyntheticJawPair& pair, const io::SyntheticJawOptions& options) {
  std::ostringstream s;
  s.precision(17);
  s << "{\n  \"generator\": {\"triangles_per_jaw\": " << options.triangles_per_jaw
    << ", \"seed\": " << options.seed << "},\n"
    << "  \"convention\": \"upper.stl and lower.stl are both in the lower jaw frame L at the "
       "ground-truth bite; X_LU is the pose of the upper jaw's own frame U in L (upper.stl = "
       "X_LU * upper in U)\",\n"
    << "  \"X_LU\": " << MatrixJson(pair.X_LU.matrix()) << ",\n"
    << "  \"occlusal_axis_L\": [" << pair.occlusal_axis_L.x() << ", " << pair.occlusal_axis_L.y()
    << ", " << pair.occlusal_axis_L.z() << "],\n  \"contacts\": [";
  for (std::size_t i = 0; i < pair.contacts.size(); ++i) {
    const auto& c = pair.contacts[i];
    s << (i ? ",\n    " : "\n    ") << "{\"p_L\": [" << c.p_L.x() << ", " << c.p_L.y() << ", "
      << c.p_L.z() << "], \"upper_tooth\": " << c.upper_tooth
      << ", \"lower_tooth\": " << c.lower_tooth << "}";
  }
  s << "\n  ],\n  \"triangles\": {\"upper\": " << pair.upper_U.num_triangles()
    << ", \"lower\": " << pair.lower_L.num_triangles() << "}\n}\n";
  return s.str();
}

}  // namespace

io::SyntheticJawPair MakeSyntheticOrExplain(const io::SyntheticJawOptions& options) {
  try {
    return io::MakeSyntheticJawPair(options);
  } catch (const std::invalid_argument& e) {
    throw UserError(std::string("--triangles: ") + e.what());
  }
}

void WriteSyntheticCase(const io::SyntheticJawPair& pair, const io::SyntheticJawOptions& options,
                        const std::filesystem::path& dir) {
  PrepareOutputDir(dir);
  try {
    io::WriteBinaryStl(pair.upper_U.Transformed(pair.X_LU), dir / "upper.stl",
                       "occlude synthetic upper jaw (frame L, mm)");
    io::WriteBinaryStl(pair.lower_L, dir / "lower.stl",
                       "occlude synthetic lower jaw (frame L, mm)");
  } catch (const io::MeshError& e) {
    throw UserError(e.what());
  }
  WriteFileAtomic(dir / "truth.json", TruthJson(pair, options));
}

void AddSynthCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "synth", "Write the procedural synthetic jaw pair (STL + ground-truth pose) to a folder");
  struct Args {
    std::size_t triangles = 20000;
    std::uint32_t seed = 1;
    std::string out;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("--triangles", args->triangles, "Triangle budget per jaw (5000..500000)")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Generator seed")->capture_default_str();
  cmd->add_option("--out", args->out, "Output folder")->required();
  cmd->callback([args] {
    io::SyntheticJawOptions options;
    options.triangles_per_jaw = args->triangles;
    options.seed = args->seed;
    const io::SyntheticJawPair pair = MakeSyntheticOrExplain(options);
    WriteSyntheticCase(pair, options, args->out);
    std::cout << "synth: wrote " << args->out << "/upper.stl (" << pair.upper_U.num_triangles()
              << " triangles), lower.stl (" << pair.lower_L.num_triangles()
              << " triangles) and truth.json (" << pair.contacts.size() << " known contacts)\n";
  });
}

}  // namespace occlude::app
