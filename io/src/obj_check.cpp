// OBJ pre-check: walks the 'v' and 'f' lines of an OBJ before assimp imports it,
// rejecting binary data, malformed or non-finite coordinates, faces with fewer
// than 3 corners and vertex indices outside the file (1-based, or negative =
// relative to the vertices so far), with the line number; and writes the
// canonical "v x y z" / "f i j k ..." text that assimp is given instead.
#include <cmath>
#include <string>

#include "mesh_io_internal.h"
#include "mesh_io_text.h"

namespace occlude::io::detail {
namespace {

namespace fs = std::filesystem;

// Running totals of the walk, for the checks that need the whole file.
struct ObjTally {
  long long vertices = 0;
  long long faces = 0;
  long long max_index = 0;  // largest absolute face index seen
  int max_index_line = 0;
};

[[noreturn]] void FailLine(const fs::path& file, int line, const std::string& what) {
  Fail(file, "line " + std::to_string(line) + ": " + what);
}

void CheckTextBytes(const fs::path& file, int line, std::string_view text) {
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && !IsSpace(c)) || u == 0x7f) {
      FailLine(file, line, "binary data (byte " + std::to_string(u) + "): not a text OBJ file");
    }
  }
}

// Appends "v x y z\n" (extra values such as w or colours are left out).
void CheckVertexLine(const fs::path& file, int line, std::string_view rest, std::string& out) {
  out += 'v';
  for (int i = 0; i < 3; ++i) {
    const std::string_view token = PopToken(&rest);
    double value = 0.0;
    if (token.empty()) FailLine(file, line, "'v' needs 3 coordinates");
    if (!ParseReal(token, &value)) FailLine(file, line, Quote(token) + " is not a number");
    if (!std::isfinite(value)) {
      FailLine(file, line,
               "non-finite vertex coordinate " + Quote(token) +
                   "; the file is corrupt: export it again");
    }
    out += ' ';
    out += FormatNumber(value);
  }
  out += '\n';
}

// Appends "f i j k ...\n" with absolute 1-based vertex indices (texture and
// normal indices are left out).
void CheckFaceLine(const fs::path& file, int line, std::string_view rest, ObjTally& tally,
                   std::string& out) {
  out += 'f';
  int corners = 0;
  for (std::string_view token = PopToken(&rest); !token.empty(); token = PopToken(&rest)) {
    const std::string_view index_text = token.substr(0, token.find('/'));
    long long index = 0;
    if (!ParseInt(index_text, &index) || index == 0) {
      FailLine(file, line, Quote(token) + " is not a vertex index (1-based)");
    }
    if (index < 0) {
      if (tally.vertices + index < 0) {
        FailLine(file, line,
                 "relative index " + std::to_string(index) + " reaches before the first vertex");
      }
      index += tally.vertices + 1;
    }
    if (index > tally.max_index) {
      tally.max_index = index;
      tally.max_index_line = line;
    }
    out += ' ';
    out += std::to_string(index);
    ++corners;
  }
  if (corners < 3) {
    FailLine(file, line, "a face needs at least 3 vertices, found " + std::to_string(corners));
  }
  out += '\n';
  ++tally.faces;
}

}  // namespace

std::string CanonicalObjText(const fs::path& file, std::string_view text) {
  std::string canonical;
  canonical.reserve(text.size());
  LineReader lines(text);
  ObjTally tally;
  std::string_view line;
  while (lines.Next(&line)) {
    CheckTextBytes(file, lines.line_number(), line);
    std::string_view rest = line;
    const std::string_view keyword = PopToken(&rest);
    if (keyword == "v") {
      CheckVertexLine(file, lines.line_number(), rest, canonical);
      ++tally.vertices;
    } else if (keyword == "f") {
      CheckFaceLine(file, lines.line_number(), rest, tally, canonical);
    }
  }
  if (tally.faces == 0) {
    Fail(file, tally.vertices == 0
                   ? "not an OBJ mesh: no 'v' or 'f' lines"
                   : "contains no faces ('f' lines), only " + std::to_string(tally.vertices) +
                         " vertices; a point cloud is not a surface");
  }
  if (tally.max_index > tally.vertices) {
    FailLine(file, tally.max_index_line,
             "a face refers to vertex " + std::to_string(tally.max_index) +
                 " but the file has only " + std::to_string(tally.vertices) +
                 " vertices ('v' lines); the file is corrupt: export it again");
  }
  return canonical;
}

}  // namespace occlude::io::detail
