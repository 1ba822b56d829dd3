// Shared machinery of the input suites (bad_input_test.cpp, odd_input_test.cpp):
// the commands as a user runs them, a good case to start from, and one run of a
// command on inputs of which one has been changed. To cover a new command
// (propose, refine, validate), add its row to Commands(): every input of the
// kinds it reads then runs through it.
#pragma once

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "occlude/io/mesh_io.h"
#include "run_occlude.h"
#include "test_common.h"

namespace occlude::test::suite {

namespace fs = std::filesystem;

/// What a command reads (bits).
enum Reads : unsigned {
  kMeshes = 1,      ///< mesh files named on the command line or in the config
  kConfig = 2,      ///< a case config file
  kPose = 4,        ///< a pose file
  kOut = 8,         ///< an output folder
  kCaseFolder = 16  ///< a case folder holding lower.stl and upper.stl
};

/// One way to run a command. Placeholders: {lower} {upper} {pose} {config} {case}
/// and {out} ("--out DIR", or nothing when the folder comes from the config);
/// {extra} is where an input adds options.
struct CommandForm {
  const char* name;
  const char* args;
  unsigned reads;
};

/// The commands under test, at coarse voxels so that each run is short.
inline const std::vector<CommandForm>& Commands() {
  static const std::vector<CommandForm> commands = {
      {"collide", "collide --lower {lower} --upper {upper} --voxel 0.8 --pose {pose} {out} {extra}",
       kMeshes | kPose | kOut},
      {"report", "report {config} --pose {pose} {out} {extra}", kMeshes | kConfig | kPose | kOut},
      {"bench", "bench --case {case} --voxel 0.8 --reps 1 --offsets 0 --no-fcl {out} {extra}",
       kCaseFolder | kOut},
  };
  return commands;
}

/// The inputs of one run: the good case, until an input changes one of them.
struct Inputs {
  fs::path dir;                  ///< this run's folder (everything below is in it)
  fs::path lower, upper, pose;   ///< mesh files and pose file
  std::string config;            ///< case config text ({lower}, {upper} replaced when written)
  fs::path config_file;          ///< where the config is written
  bool write_config = true;      ///< false: leave config_file as it is (missing, a folder)
  fs::path out;                  ///< output folder
  bool out_from_config = false;  ///< run without --out: the config's [output] folder
  bool unprivileged = false;     ///< run as the user nobody (permission cases)
  std::string extra;             ///< more options
};

/// Lines of `text`.
inline std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// A readable test name part: letters, digits and '_' only.
inline std::string NamePart(const std::string& text) {
  std::string out;
  for (const char c : text) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

/// rwxr-xr-x: the user nobody must reach the files of unprivileged runs.
inline void OpenToEveryone(const fs::path& path) {
  using fs::perms;
  fs::permissions(path, perms::owner_all | perms::group_read | perms::group_exec |
                            perms::others_read | perms::others_exec);
}

/// Folder of the good case: lower.stl, a 20 x 10 x 20 mm box with its top at y = 0,
/// and upper.stl, a 16 x 8 x 16 mm box resting 0.05 mm above it (in contact within
/// the default band). Written once per process; boxes keep every run short, also
/// under the sanitizers (each test is its own process).
inline const fs::path& GoodCase() {
  static const TempDir* dir = [] {
    auto* d = new TempDir;  // lives until the process ends
    OpenToEveryone(d->path());
    fs::create_directory(*d / "case");
    OpenToEveryone(*d / "case");
    io::WriteBinaryStl(MakeBox({0, -10, 0}, {20, 0, 20}), *d / "case" / "lower.stl");
    io::WriteBinaryStl(MakeBox({2, 0.05, 2}, {18, 8.05, 18}), *d / "case" / "upper.stl");
    return d;
  }();
  static const fs::path path = *dir / "case";
  return path;
}

/// Writes a 12-triangle binary STL box of `size_mm` to `file` and returns its bytes.
inline std::string WriteBox(const fs::path& file, double size_mm = 10.0) {
  io::WriteBinaryStl(MakeBox({0, 0, 0}, {size_mm, size_mm, size_mm}), file);
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Fresh inputs in `dir`: the good meshes, an identity pose file, a config
/// naming the meshes at voxel 0.8 mm, and dir/out as output folder.
inline Inputs GoodInputs(const fs::path& dir) {
  Inputs in;
  in.dir = dir;
  OpenToEveryone(dir);
  in.lower = GoodCase() / "lower.stl";
  in.upper = GoodCase() / "upper.stl";
  in.pose = dir / "pose.json";
  std::ofstream(in.pose) << R"({"X_LU": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})";
  in.config =
      "[lower]\nfile = \"{lower}\"\n[upper]\nfile = \"{upper}\"\n[accuracy]\nvoxel_mm = 0.8\n";
  in.config_file = dir / "case.toml";
  in.out = dir / "out";
  return in;
}

/// Files (not folders) below `dir`, as relative paths.
inline std::set<std::string> FilesBelow(const fs::path& dir) {
  std::set<std::string> files;
  std::error_code ec;
  for (auto it =
           fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied, ec);
       it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    if (!it->is_directory(ec)) files.insert(fs::relative(it->path(), dir, ec).string());
  }
  return files;
}

/// Copies what `from` is (a file with its permissions, a folder, or nothing) to `to`.
inline void Mirror(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(from, ec);
  if (status.type() == fs::file_type::directory) {
    fs::create_directory(to);
  } else if (status.type() == fs::file_type::regular) {
    fs::copy_file(from, to);
    fs::permissions(to, status.permissions());
  }
}

inline void Replace(std::string* text, const std::string& key, const std::string& value) {
  for (std::size_t at; (at = text->find(key)) != std::string::npos;)
    text->replace(at, key.size(), value);
}

/// A run ready to start: the command line and what to put before the binary.
struct PreparedRun {
  std::string prefix;  ///< "" or the switch to the user nobody
  std::string args;
  std::string skipped;  ///< why the run cannot happen here (then nothing else is set)
};

/// Prepares `form` on `in`: writes the config and the case folder, fills the
/// placeholders. Sets `skipped` when the run must be unprivileged and cannot be.
inline PreparedRun Prepare(const CommandForm& form, const Inputs& in) {
  PreparedRun run;
  if (in.unprivileged) {
    std::string why;
    const auto p = UnprivilegedPrefix(&why);
    if (!p) {
      run.skipped = "cannot run as an unprivileged user: " + why;
      return run;
    }
    run.prefix = *p;
    // nobody may not create folders in this run's folder (root's): give it the output folder.
    if (!fs::exists(in.out) && !in.out_from_config) {
      fs::create_directory(in.out);
      fs::permissions(in.out, fs::perms::all);
    }
  }
  if (in.write_config) {
    std::string config = in.config;
    Replace(&config, "{lower}", in.lower.string());
    Replace(&config, "{upper}", in.upper.string());
    std::ofstream(in.config_file, std::ios::app) << config;
  }
  const fs::path case_dir = in.dir / "bench-case";
  if ((form.reads & kCaseFolder) != 0 && !fs::exists(case_dir)) {
    fs::create_directory(case_dir);
    OpenToEveryone(case_dir);
    Mirror(in.lower, case_dir / "lower.stl");
    Mirror(in.upper, case_dir / "upper.stl");
  }
  run.args = form.args;
  Replace(&run.args, "{lower}", in.lower.string());
  Replace(&run.args, "{upper}", in.upper.string());
  Replace(&run.args, "{pose}", in.pose.string());
  Replace(&run.args, "{config}", in.config_file.string());
  Replace(&run.args, "{case}", case_dir.string());
  Replace(&run.args, "{out}", in.out_from_config ? std::string() : "--out " + in.out.string());
  Replace(&run.args, "{extra}", in.extra);
  return run;
}

inline CommandRun RunPrepared(const PreparedRun& run) {
  return OccludeWithPrefix(run.prefix, run.args);
}

}  // namespace occlude::test::suite
