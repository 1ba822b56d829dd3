// Atomic output files (see output_files.h).
#include "base/output_files.h"

#include <unistd.h>

#include <sstream>

#include "base/user_error.h"
#include "occlude/io/atomic_file.h"
#include "occlude/io/mesh_io.h"

namespace occlude::app {

void PrepareOutputDir(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw UserError(dir.string() +
                    ": output path exists and is not a folder; choose another --out");
  }
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    throw UserError(dir.string() + ": cannot create the output folder (" + ec.message() +
                    "); choose a writable --out");
  }
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw UserError(dir.string() + ": output folder is not writable; choose a writable --out");
  }
}

void WriteFileAtomic(const std::filesystem::path& file, const std::string& content) {
  try {
    io::WriteFileAtomically(file, content);
  } catch (const io::MeshError& e) {
    throw UserError(e.what());
  }
}

std::string MatrixJson(const Eigen::Matrix4d& m) {
  std::ostringstream s;
  s.precision(17);
  s << "[";
  for (int r = 0; r < 4; ++r) {
    s << (r ? ", [" : "[");
    for (int c = 0; c < 4; ++c) s << (c ? ", " : "") << m(r, c);
    s << "]";
  }
  s << "]";
  return s.str();
}

}  // namespace occlude::app
