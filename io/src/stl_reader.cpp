// STL reader: binary and ASCII STL into a RawMesh (file units, 3 positions per
// facet). Binary vs ASCII is decided by content: a file whose size is exactly
// 84 + 50 * (header triangle count) is binary, even when it starts with "solid"
// as many exporters' binary files do; otherwise it must be ASCII text starting
// with "solid". Nothing is allocated by a count the file size does not back.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "mesh_io_internal.h"
#include "mesh_io_text.h"

namespace occlude::io::detail {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kTextProbeBytes = 1024;

std::uint32_t ReadU32(const char* p) {
  const auto* b = reinterpret_cast<const unsigned char*>(p);
  return static_cast<std::uint32_t>(b[0]) | (static_cast<std::uint32_t>(b[1]) << 8) |
         (static_cast<std::uint32_t>(b[2]) << 16) | (static_cast<std::uint32_t>(b[3]) << 24);
}

// Little-endian IEEE float at p, as double (exact).
double ReadF32(const char* p) {
  const std::uint32_t bits = ReadU32(p);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return static_cast<double>(value);
}

Eigen::Vector3d ReadVertex(const char* p) { return {ReadF32(p), ReadF32(p + 4), ReadF32(p + 8)}; }

// True when the first bytes are plain text (printable, whitespace or UTF-8).
bool LooksLikeText(std::string_view bytes) {
  const std::size_t n = std::min(bytes.size(), kTextProbeBytes);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if ((c < 0x20 && !IsSpace(bytes[i])) || c == 0x7f) return false;
  }
  return true;
}

bool StartsWithSolid(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && IsSpace(bytes[i])) ++i;
  return StartsWithNoCase(bytes.substr(i), "solid");
}

// Whether the complete records present look like STL triangles (finite vertices
// of sane magnitude): tells "truncated STL" from "not an STL file at all".
bool RecordsLookPlausible(std::string_view bytes) {
  constexpr double kAbsurd = 1e7;
  constexpr std::size_t kProbeRecords = 64;
  const std::size_t present = (bytes.size() - kStlPreambleBytes) / kStlRecordBytes;
  if (present == 0) return false;
  for (std::size_t t = 0; t < std::min(present, kProbeRecords); ++t) {
    const char* record = bytes.data() + kStlPreambleBytes + t * kStlRecordBytes;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d v = ReadVertex(record + 12 + 12 * k);
      if (!v.allFinite() || v.cwiseAbs().maxCoeff() > kAbsurd) return false;
    }
  }
  return true;
}

[[noreturn]] void FailSizeMismatch(const fs::path& file, std::string_view bytes) {
  const std::uint64_t count = ReadU32(bytes.data() + 80);
  const std::uint64_t expected = kStlPreambleBytes + kStlRecordBytes * count;
  const std::uint64_t size = bytes.size();
  std::string what = "binary STL header says " + std::to_string(count) +
                     " triangles, which needs " + std::to_string(expected) +
                     " bytes, but the file has " + std::to_string(size) + " bytes; ";
  if (!RecordsLookPlausible(bytes)) {
    what += "the data does not look like STL triangles either: this is not an STL file";
  } else if (size < expected) {
    what += "the file is truncated (or its header count is wrong): export or copy it again";
  } else if ((size - kStlPreambleBytes) % kStlRecordBytes == 0) {
    what += "the size fits " + std::to_string((size - kStlPreambleBytes) / kStlRecordBytes) +
            " triangles, so the header count is wrong: export the mesh again";
  } else {
    what += "the file is corrupt: export it again";
  }
  Fail(file, what);
}

RawMesh ReadBinaryStl(const fs::path& file, std::string_view bytes) {
  const std::size_t count = ReadU32(bytes.data() + 80);
  if (count == 0) Fail(file, "contains no triangles (binary STL with a count of 0)");
  RawMesh raw;
  raw.positions.reserve(3 * count);  // backed by the file size, checked by the caller
  raw.triangles.reserve(count);
  for (std::size_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + kStlPreambleBytes + t * kStlRecordBytes;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d v = ReadVertex(record + 12 + 12 * k);
      if (!v.allFinite()) {
        Fail(file, "triangle " + std::to_string(t + 1) + " of " + std::to_string(count) +
                       " has a non-finite vertex coordinate (NaN or infinity); the file is "
                       "corrupt: export it again");
      }
      raw.positions.push_back(v);
    }
    const int first = static_cast<int>(3 * t);
    raw.triangles.emplace_back(first, first + 1, first + 2);
  }
  return raw;
}

// Recursive-descent reader of ASCII STL: one or more
// "solid .. facet normal n n n outer loop vertex x y z (x3) endloop endfacet .. endsolid".
// Keywords are case-insensitive; normals may be non-finite (they are ignored),
// vertices may not.
class AsciiStlReader {
 public:
  AsciiStlReader(const fs::path& file, std::string_view text) : file_(file), tokens_(text) {}

  RawMesh Read() {
    tokens_.Next();  // "solid", checked by the caller
    tokens_.SkipRestOfLine();
    for (;;) {
      const std::string_view token = tokens_.Next();
      if (EqualsNoCase(token, "facet")) {
        ReadFacet();
      } else if (EqualsNoCase(token, "endsolid")) {
        if (!ReadAfterEndsolid()) break;
      } else if (token.empty()) {
        FailAt("the file ends without 'endsolid', so it is truncated: export or copy it again");
      } else {
        FailAt("expected 'facet' or 'endsolid', found " + Quote(token));
      }
    }
    if (facets_ == 0) Fail(file_, "contains no triangles (ASCII STL without facets)");
    return std::move(raw_);
  }

 private:
  // After "endsolid": true when another "solid" follows.
  bool ReadAfterEndsolid() {
    tokens_.SkipRestOfLine();
    const std::string_view token = tokens_.Next();
    if (token.empty()) return false;
    if (EqualsNoCase(token, "solid")) {
      tokens_.SkipRestOfLine();
      return true;
    }
    raw_.warnings.push_back(
        Line(file_, "ignored text after 'endsolid' from line " + std::to_string(tokens_.line())));
    return false;
  }

  void ReadFacet() {
    ++facets_;
    Expect("normal");
    for (int i = 0; i < 3; ++i) Number(/*vertex=*/false);
    Expect("outer");
    Expect("loop");
    const int first = static_cast<int>(raw_.positions.size());
    for (int k = 0; k < 3; ++k) {
      Expect("vertex");
      Eigen::Vector3d v;
      for (int i = 0; i < 3; ++i) v[i] = Number(/*vertex=*/true);
      raw_.positions.push_back(v);
    }
    Expect("endloop");
    Expect("endfacet");
    raw_.triangles.emplace_back(first, first + 1, first + 2);
  }

  void Expect(std::string_view keyword) {
    const std::string_view token = tokens_.Next();
    if (EqualsNoCase(token, keyword)) return;
    if (token.empty()) {
      FailAt("the file ends inside facet " + std::to_string(facets_) + " where '" +
             std::string(keyword) + "' was expected, so it is truncated: export or copy it again");
    }
    FailAt("expected '" + std::string(keyword) + "' in facet " + std::to_string(facets_) +
           ", found " + Quote(token));
  }

  double Number(bool vertex) {
    const std::string_view token = tokens_.Next();
    const char* what = vertex ? "vertex coordinate" : "normal component";
    if (token.empty()) {
      FailAt("the file ends inside facet " + std::to_string(facets_) + " where a " + what +
             " was expected, so it is truncated: export or copy it again");
    }
    double value = 0.0;
    if (!ParseReal(token, &value)) {
      FailAt(Quote(token) + " is not a number (" + what + " in facet " + std::to_string(facets_) +
             "); the file is corrupt");
    }
    if (vertex && !std::isfinite(value)) {
      FailAt("non-finite vertex coordinate " + Quote(token) + " in facet " +
             std::to_string(facets_) + "; the file is corrupt: export it again");
    }
    return value;
  }

  [[noreturn]] void FailAt(const std::string& what) {
    Fail(file_, "line " + std::to_string(tokens_.line()) + ": " + what);
  }

  const fs::path& file_;
  Tokenizer tokens_;
  RawMesh raw_;
  std::size_t facets_ = 0;
};

}  // namespace

RawMesh ReadStl(const fs::path& file, std::string_view bytes) {
  if (bytes.size() >= kStlPreambleBytes) {
    const std::uint64_t count = ReadU32(bytes.data() + 80);
    if (bytes.size() == kStlPreambleBytes + kStlRecordBytes * count)
      return ReadBinaryStl(file, bytes);
  }
  const std::string_view text = WithoutUtf8Bom(bytes);
  if (StartsWithSolid(text) && LooksLikeText(text)) return AsciiStlReader(file, text).Read();
  if (LooksLikeText(bytes)) {
    Fail(file, "not an STL file: it is text but does not start with 'solid'");
  }
  if (bytes.size() < kStlPreambleBytes) {
    Fail(file, "not an STL file: " + std::to_string(bytes.size()) +
                   " bytes is shorter than a binary STL header (84 bytes)");
  }
  FailSizeMismatch(file, bytes);
}

}  // namespace occlude::io::detail
