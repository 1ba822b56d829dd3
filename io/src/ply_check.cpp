// PLY pre-check: parses the header and walks every element of the body (ASCII
// or binary, either endianness), rejecting a truncated body, counts the file
// does not back, non-numeric values, non-finite vertex coordinates and face
// indices outside the vertex list; nothing is allocated by the header's counts.
// What assimp then imports is a canonical binary PLY of the walked vertices and
// faces: assimp 5.2's own PLY reader misreads ASCII elements that share a line,
// rejects faces declared before vertices, leaks on triangle strips, and drops
// a binary body's first byte when it is 0x0A (then fails, leaking the mesh).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "mesh_io_internal.h"
#include "mesh_io_text.h"

namespace occlude::io::detail {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

struct PlyType {
  int size = 0;   // bytes in binary files; 0 = unknown type
  char kind = 0;  // 'i' signed integer, 'u' unsigned integer, 'f' floating point
};

struct PlyProperty {
  std::string name;
  PlyType type;  // of the value, or of each list item
  bool is_list = false;
  PlyType count_type;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  enum class Format { kAscii, kLittleEndian, kBigEndian } format = Format::kAscii;
  std::vector<PlyElement> elements;
  std::uint64_t vertex_count = 0;
  std::size_t body_offset = 0;
  int lines = 0;
};

PlyType TypeNamed(std::string_view name) {
  if (name == "char" || name == "int8") return {1, 'i'};
  if (name == "uchar" || name == "uint8") return {1, 'u'};
  if (name == "short" || name == "int16") return {2, 'i'};
  if (name == "ushort" || name == "uint16") return {2, 'u'};
  if (name == "int" || name == "int32") return {4, 'i'};
  if (name == "uint" || name == "uint32") return {4, 'u'};
  if (name == "float" || name == "float32") return {4, 'f'};
  if (name == "double" || name == "float64") return {8, 'f'};
  return {};
}

bool IsFaceIndexList(const PlyElement& element, const PlyProperty& property) {
  return element.name == "face" && property.is_list &&
         (property.name == "vertex_indices" || property.name == "vertex_index");
}

bool IsCoordinate(const PlyElement& element, const PlyProperty& property) {
  return element.name == "vertex" && !property.is_list &&
         (property.name == "x" || property.name == "y" || property.name == "z");
}

// --- header -----------------------------------------------------------------

class HeaderParser {
 public:
  HeaderParser(const fs::path& file, std::string_view bytes) : file_(file), lines_(bytes) {}

  PlyHeader Parse() {
    std::string_view line;
    if (!lines_.Next(&line) || !EqualsNoCase(Trimmed(line), "ply")) {
      Fail(file_, "not a PLY file: it does not start with 'ply'");
    }
    while (lines_.Next(&line)) {
      if (lines_.offset() > kMaxHeaderBytes) break;
      std::string_view rest = line;
      const std::string_view keyword = PopToken(&rest);
      if (keyword == "end_header") return Finish();
      ParseLine(keyword, rest);
    }
    Fail(file_, "no 'end_header' line: not a PLY file, or its header is corrupt");
  }

 private:
  static std::string_view Trimmed(std::string_view text) { return PopToken(&text); }

  void ParseLine(std::string_view keyword, std::string_view rest) {
    if (keyword == "format") {
      const std::string_view format = PopToken(&rest);
      if (format == "ascii") {
        header_.format = PlyHeader::Format::kAscii;
      } else if (format == "binary_little_endian") {
        header_.format = PlyHeader::Format::kLittleEndian;
      } else if (format == "binary_big_endian") {
        header_.format = PlyHeader::Format::kBigEndian;
      } else {
        FailHere("unknown PLY format " + Quote(format));
      }
    } else if (keyword == "element") {
      ParseElement(rest);
    } else if (keyword == "property") {
      ParseProperty(rest);
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      FailHere("unexpected header line starting with " + Quote(keyword));
    }
  }

  void ParseElement(std::string_view rest) {
    PlyElement element;
    element.name = std::string(PopToken(&rest));
    const std::string_view count_text = PopToken(&rest);
    long long count = 0;
    if (element.name.empty() || !ParseInt(count_text, &count) || count < 0) {
      FailHere("'element' needs a name and a count, found count " + Quote(count_text));
    }
    element.count = static_cast<std::uint64_t>(count);
    header_.elements.push_back(std::move(element));
  }

  void ParseProperty(std::string_view rest) {
    if (header_.elements.empty()) FailHere("'property' before any 'element'");
    PlyProperty property;
    std::string_view type_name = PopToken(&rest);
    if (type_name == "list") {
      property.is_list = true;
      const std::string_view count_name = PopToken(&rest);
      property.count_type = TypeNamed(count_name);
      if (property.count_type.size == 0 || property.count_type.kind == 'f') {
        FailHere("list count type " + Quote(count_name) + " is not an integer type");
      }
      type_name = PopToken(&rest);
    }
    property.type = TypeNamed(type_name);
    if (property.type.size == 0) FailHere("unknown property type " + Quote(type_name));
    property.name = std::string(PopToken(&rest));
    header_.elements.back().properties.push_back(std::move(property));
  }

  PlyHeader Finish() {
    header_.body_offset = lines_.offset();
    header_.lines = lines_.line_number();
    int vertex_elements = 0;
    int face_lists = 0;
    std::string coordinates;  // the x, y, z property names seen, in order
    for (const PlyElement& element : header_.elements) {
      for (const PlyProperty& property : element.properties) {
        if (IsFaceIndexList(element, property)) face_lists += element.count > 0 ? 1 : 0;
        if (IsCoordinate(element, property)) coordinates += property.name;
      }
      if (element.name == "vertex") {
        header_.vertex_count = element.count;
        ++vertex_elements;
      }
    }
    std::sort(coordinates.begin(), coordinates.end());
    if (vertex_elements != 1 || coordinates != "xyz") {
      Fail(file_, "the PLY needs one 'vertex' element with properties x, y and z once each");
    }
    if (face_lists == 0) Fail(file_, "contains no faces; a point cloud is not a surface");
    if (face_lists > 1) Fail(file_, "the PLY has more than one list of face vertex indices");
    if (header_.vertex_count > UINT32_MAX) Fail(file_, "the PLY has too many vertices");
    return std::move(header_);
  }

  [[noreturn]] void FailHere(const std::string& what) {
    Fail(file_, "line " + std::to_string(lines_.line_number()) + ": " + what);
  }

  const fs::path& file_;
  LineReader lines_;
  PlyHeader header_;
};

// --- body ---------------------------------------------------------------------

// Reads one value at a time from the body, ASCII or binary; false at the end.
class ValueReader {
 public:
  ValueReader(const PlyHeader& header, std::string_view body)
      : format_(header.format), body_(body), tokens_(body) {}

  // Binary: decodes a value of `type` into `*value`. ASCII: sets `*text` to the
  // next token, unparsed. False at the end of the body.
  bool Read(PlyType type, double* value, std::string_view* text) {
    if (format_ == PlyHeader::Format::kAscii) {
      *text = tokens_.Next();
      return !text->empty();
    }
    if (body_.size() - pos_ < static_cast<std::size_t>(type.size)) return false;
    *value = Decode(type, body_.data() + pos_);
    pos_ += static_cast<std::size_t>(type.size);
    return true;
  }

  bool ascii() const { return format_ == PlyHeader::Format::kAscii; }
  int line() const { return tokens_.line(); }
  bool AtEnd() {
    if (!ascii()) return pos_ == body_.size();
    return tokens_.Next().empty();
  }

 private:
  double Decode(PlyType type, const char* p) const {
    std::uint64_t bits = 0;
    for (int i = 0; i < type.size; ++i) {
      const int byte = format_ == PlyHeader::Format::kLittleEndian ? i : type.size - 1 - i;
      bits |= static_cast<std::uint64_t>(static_cast<unsigned char>(p[byte])) << (8 * i);
    }
    if (type.kind == 'u') return static_cast<double>(bits);
    if (type.kind == 'i') {
      const int shift = 64 - 8 * type.size;
      return static_cast<double>(static_cast<std::int64_t>(bits << shift) >> shift);
    }
    if (type.size == 4) {
      const auto bits32 = static_cast<std::uint32_t>(bits);
      float f;
      std::memcpy(&f, &bits32, sizeof f);
      return static_cast<double>(f);
    }
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }

  PlyHeader::Format format_;
  std::string_view body_;
  std::size_t pos_ = 0;
  Tokenizer tokens_;
};

// Walks every value of the body and writes the canonical binary PLY that
// assimp is given: "vertex" (float x, y, z) then "face" (uint count, uint
// indices), whatever the file's format, property order or element order.
class BodyWalker {
 public:
  BodyWalker(const fs::path& file, const PlyHeader& header, std::string_view bytes)
      : file_(file), header_(header), values_(header, bytes.substr(header.body_offset)) {}

  std::string Walk(std::vector<std::string>* warnings) {
    for (const PlyElement& element : header_.elements) {
      const bool vertex = element.name == "vertex";
      if (!vertex && element.name != "face" && element.count > 0) {
        warnings->push_back(Line(file_, "ignored PLY element '" + element.name + "' (" +
                                            std::to_string(element.count) +
                                            " items); only vertices and faces are read"));
      }
      // An element without properties occupies no bytes, whatever its count: walking
      // its (up to 2^63) items would only spin.
      if (element.properties.empty()) continue;
      for (std::uint64_t k = 0; k < element.count; ++k) {
        for (const PlyProperty& property : element.properties) {
          WalkProperty(element, k, property);
        }
        if (vertex) AppendVertex();
      }
    }
    if (!values_.AtEnd()) {
      warnings->push_back(Line(file_, "ignored data after the last PLY element"));
    }
    // Each vertex starts with a guard byte because assimp 5.2 swallows a 0x0A
    // byte right after "end_header" (as when the first x is 0.02f).
    return "ply\nformat binary_little_endian 1.0\nelement vertex " +
           std::to_string(header_.vertex_count) +
           "\nproperty uchar guard\nproperty float x\nproperty float y\nproperty float z\n"
           "element face " +
           std::to_string(faces_) + "\nproperty list uint uint vertex_indices\nend_header\n" +
           vertex_bytes_ + face_bytes_;
  }

 private:
  void WalkProperty(const PlyElement& element, std::uint64_t k, const PlyProperty& property) {
    if (!property.is_list) {
      const double value = Value(element, k, property, property.type);
      if (IsCoordinate(element, property)) {
        if (!std::isfinite(value)) {
          FailAt("vertex " + std::to_string(k) +
                 " has a non-finite coordinate (NaN or infinity); the file is corrupt: export "
                 "it again");
        }
        if (std::abs(value) > static_cast<double>(FLT_MAX)) {
          FailAt("vertex " + std::to_string(k) + " has a coordinate beyond the float range");
        }
        xyz_[static_cast<std::size_t>(property.name[0] - 'x')] = static_cast<float>(value);
      }
      return;
    }
    const double count = Value(element, k, property, property.count_type);
    if (count < 0 || count != std::floor(count)) {
      FailAt("bad list length " + FormatNumber(count) + " in " + element.name + " " +
             std::to_string(k));
    }
    const bool face = IsFaceIndexList(element, property);
    if (face && (count < 3 || count > UINT32_MAX)) {
      FailAt("face " + std::to_string(k) + " has " + FormatNumber(count) +
             " vertices; a face needs at least 3");
    }
    if (face) AppendU32(static_cast<std::uint32_t>(count), face_bytes_);
    for (double i = 0; i < count; ++i) {
      const double index = Value(element, k, property, property.type);
      if (!face) continue;
      if (!(index >= 0 && index < static_cast<double>(header_.vertex_count) &&
            index == std::floor(index))) {
        FailAt("face " + std::to_string(k) + " refers to vertex " + FormatNumber(index) +
               ", but the file has only " + std::to_string(header_.vertex_count) +
               " vertices (0-based); the file is corrupt: export it again");
      }
      AppendU32(static_cast<std::uint32_t>(index), face_bytes_);  // < vertex_count < 2^32
    }
    if (face) ++faces_;
  }

  double Value(const PlyElement& element, std::uint64_t k, const PlyProperty& property,
               PlyType type) {
    double value = 0.0;
    std::string_view text;
    if (!values_.Read(type, &value, &text)) {
      FailAt("the PLY ends inside " + element.name + " " + std::to_string(k) + " of " +
             std::to_string(element.count) +
             ", so it is truncated (or its header counts are wrong): export or copy it again");
    }
    if (values_.ascii() && !ParseReal(text, &value)) {
      FailAt(Quote(text) + " is not a number (property '" + property.name + "' of " + element.name +
             " " + std::to_string(k) + ")");
    }
    return value;
  }

  static void AppendU32(std::uint32_t value, std::string& out) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>((value >> (8 * i)) & 0xffu);
  }

  void AppendVertex() {
    vertex_bytes_ += 'G';
    for (const float f : xyz_) {
      std::uint32_t bits;
      std::memcpy(&bits, &f, sizeof bits);
      AppendU32(bits, vertex_bytes_);
    }
  }

  [[noreturn]] void FailAt(const std::string& what) {
    if (values_.ascii()) {
      Fail(file_, "line " + std::to_string(header_.lines + values_.line()) + ": " + what);
    }
    Fail(file_, what);
  }

  const fs::path& file_;
  const PlyHeader& header_;
  ValueReader values_;
  float xyz_[3] = {0, 0, 0};
  std::string vertex_bytes_;
  std::string face_bytes_;
  std::uint64_t faces_ = 0;
};

}  // namespace

std::string CanonicalPlyBytes(const fs::path& file, std::string_view bytes,
                              std::vector<std::string>* warnings) {
  const PlyHeader header = HeaderParser(file, bytes).Parse();
  return BodyWalker(file, header, bytes).Walk(warnings);
}

}  // namespace occlude::io::detail
