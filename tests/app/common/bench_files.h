// Helpers for the tests of the benchmarks and the commands that write files: a tiny analytic
// case folder (a sphere resting on a box), and reading what they write: text files, CSV rows
// as column -> cell maps ('#' lines are comments), and the size of a PNG.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "occlude/io/mesh_io.h"
#include "test_common.h"

namespace occlude::test {

/// The sphere-on-box case: lower.stl a box [-6, 6] x [-6, 6] x [-2, 0] (top face
/// z = 0), upper.stl a sphere of radius 3 about (0, 0, 3) whose south pole, a
/// vertex, touches the top face at the origin. Both in one frame (the "bite"
/// is the identity); the occlusal axis is +z. Small: a sanitizer build
/// handles its oracles in seconds.
inline constexpr double kSphereRadiusMm = 3.0;
inline io::TriangleMesh SphereOnBoxUpper() {
  return MakeSphere(Eigen::Vector3d(0, 0, kSphereRadiusMm), kSphereRadiusMm, 18, 24);
}
inline io::TriangleMesh SphereOnBoxLower() {
  return MakeBox(Eigen::Vector3d(-6, -6, -2), Eigen::Vector3d(6, 6, 0));
}
inline void WriteSphereOnBoxCase(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  io::WriteBinaryStl(SphereOnBoxLower(), dir / "lower.stl");
  io::WriteBinaryStl(SphereOnBoxUpper(), dir / "upper.stl");
}

inline std::string ReadFileText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  bool quoted = false;
  for (const char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.push_back(cell);
      cell.clear();
    } else {
      cell += c;
    }
  }
  out.push_back(cell);
  return out;
}

using CsvRow = std::map<std::string, std::string>;

/// The header line (after any '#' comments) and the rows; a row whose cell
/// count differs from the header's fails the calling test.
inline std::vector<CsvRow> ReadCsvRows(const std::filesystem::path& file,
                                       std::vector<std::string>* header_out = nullptr) {
  std::istringstream in(ReadFileText(file));
  std::string line;
  std::vector<std::string> header;
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = SplitCsvLine(line);
      continue;
    }
    const std::vector<std::string> cells = SplitCsvLine(line);
    EXPECT_EQ(cells.size(), header.size()) << file << ": " << line;
    CsvRow row;
    for (std::size_t i = 0; i < std::min(cells.size(), header.size()); ++i)
      row[header[i]] = cells[i];
    rows.push_back(row);
  }
  if (header_out) *header_out = header;
  return rows;
}

/// The number in `column` of a row.
inline double Value(const CsvRow& r, const std::string& column) { return std::stod(r.at(column)); }

/// Width and height from the IHDR chunk of PNG bytes; {0, 0} when not a PNG.
inline std::pair<int, int> PngSize(const std::string& bytes) {
  const std::string signature = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 24 || bytes.compare(0, 8, signature) != 0 ||
      bytes.compare(12, 4, "IHDR") != 0) {
    return {0, 0};
  }
  auto be32 = [&](std::size_t at) {
    int v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
    return v;
  };
  return {be32(16), be32(20)};
}

/// The same of a PNG file.
inline std::pair<int, int> PngFileSize(const std::filesystem::path& file) {
  return PngSize(ReadFileText(file));
}

}  // namespace occlude::test
