// `occlude synth`: writes the procedural synthetic jaw pair as a case folder
// (upper.stl and lower.stl in the lower jaw's frame at the ground-truth bite,
// like the real cases, plus truth.json with the pose and the known contacts, and landmarks.csv
// with the designed landmarks, which `occlude analyze --case` picks up).
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "occlude/io/synthetic_jaws.h"
#include "session/synthetic_case.h"

namespace occlude::app {

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
              << " triangles), truth.json (" << pair.contacts.size()
              << " known contacts) and landmarks.csv (" << pair.landmarks.size()
              << " designed landmarks)\n";
  });
}

}  // namespace occlude::app
