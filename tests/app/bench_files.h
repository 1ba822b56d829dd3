// Reading what the `occlude bench` modes write, for the tests of --paper and
// --accuracy: text files, CSV rows as column -> cell maps ('#' lines are
// comments), and the size of a PNG.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace occlude::test {

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

/// Width and height from a PNG's IHDR chunk; {0, 0} when not a PNG.
inline std::pair<int, int> PngFileSize(const std::filesystem::path& file) {
  const std::string bytes = ReadFileText(file);
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

}  // namespace occlude::test
