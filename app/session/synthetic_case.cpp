// The synthetic jaw pair as the commands use it (see synthetic_case.h).
#include "session/synthetic_case.h"

#include <sstream>
#include <stdexcept>
#include <string>

#include "base/output_files.h"
#include "base/user_error.h"
#include "occlude/io/landmark_file.h"
#include "occlude/io/mesh_io.h"
#include "session/case_analysis.h"

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
  WriteFileAtomic(dir / "landmarks.csv",
                  io::FormatLandmarkFile(GivenAtReference(pair.X_LU, pair.landmarks)));
}

}  // namespace occlude::app
