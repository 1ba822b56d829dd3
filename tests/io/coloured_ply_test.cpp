// The coloured PLY writer: the header in the order MeshLab and CloudCompare
// expect, the geometry read back by occlude's own PLY reader, the colours and
// distances parsed back from the body (binary and ASCII), the errors.
#include "occlude/io/coloured_ply.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "occlude/io/mesh_io.h"
#include "test_common.h"

namespace occlude::io {
namespace {

namespace fs = std::filesystem;

std::string PlyFileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A box with float-representable corners and values that exercise every byte.
struct ColouredBox {
  TriangleMesh mesh = test::MakeBox({-1.5, 2.25, 0.5}, {8.5, 12.0, 7.75});
  VertexValues values;
  ColouredBox() {
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      const auto b = static_cast<std::uint8_t>(37 * v);
      values.rgb.push_back({b, static_cast<std::uint8_t>(255 - b), static_cast<std::uint8_t>(v)});
      values.distance_mm.push_back(-0.125f + 0.0371f * static_cast<float>(v));
    }
    values.distance_mm.back() = 1e6f;  // a "far" sentinel goes through unchanged
  }
};

// The header's lines up to end_header, without comments; `body` gets the rest.
std::vector<std::string> HeaderLines(const std::string& bytes, std::string* body) {
  const std::size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream in(bytes.substr(0, end));
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("comment", 0) != 0) lines.push_back(line);
  }
  *body = bytes.substr(end + std::strlen("end_header\n"));
  return lines;
}

std::vector<std::string> ExpectedHeader(const char* format, const TriangleMesh& mesh) {
  return {"ply",
          std::string("format ") + format + " 1.0",
          "element vertex " + std::to_string(mesh.num_vertices()),
          "property float x",
          "property float y",
          "property float z",
          "property uchar red",
          "property uchar green",
          "property uchar blue",
          "property float distance_mm",
          "element face " + std::to_string(mesh.num_triangles()),
          "property list uchar int vertex_indices"};
}

template <typename T>
T ReadLittleEndian(const std::string& body, std::size_t* at) {
  T value;
  std::memcpy(&value, body.data() + *at, sizeof value);  // the test host is little-endian
  *at += sizeof value;
  return value;
}

TEST(ColouredPlyTest, HeaderListsThePropertiesInTheOrderOtherToolsExpect) {
  const ColouredBox f;
  test::TempDir dir;
  WriteColouredPly(f.mesh, f.values, dir / "m.ply");
  WriteColouredPly(f.mesh, f.values, dir / "a.ply", PlyEncoding::kAscii);
  std::string body;
  EXPECT_EQ(HeaderLines(PlyFileBytes(dir / "m.ply"), &body),
            ExpectedHeader("binary_little_endian", f.mesh));
  EXPECT_EQ(HeaderLines(PlyFileBytes(dir / "a.ply"), &body), ExpectedHeader("ascii", f.mesh));
}

TEST(ColouredPlyTest, GeometryReadsBackThroughTheProjectsPlyReader) {
  const ColouredBox f;
  test::TempDir dir;
  for (const PlyEncoding encoding : {PlyEncoding::kBinaryLittleEndian, PlyEncoding::kAscii}) {
    WriteColouredPly(f.mesh, f.values, dir / "m.ply", encoding);
    const TriangleMesh back = LoadMesh(dir / "m.ply");
    ASSERT_EQ(back.num_triangles(), f.mesh.num_triangles());
    // The box's vertices are distinct, so welding keeps them; compare corner by corner.
    for (std::size_t t = 0; t < f.mesh.num_triangles(); ++t) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(back.corner(t, k), f.mesh.corner(t, k)) << t << k;
    }
  }
}

TEST(ColouredPlyTest, BinaryColoursDistancesAndFacesRoundTrip) {
  const ColouredBox f;
  test::TempDir dir;
  WriteColouredPly(f.mesh, f.values, dir / "m.ply");
  std::string body;
  HeaderLines(PlyFileBytes(dir / "m.ply"), &body);
  ASSERT_EQ(body.size(), 19 * f.mesh.num_vertices() + 13 * f.mesh.num_triangles());
  std::size_t at = 0;
  for (std::size_t v = 0; v < f.mesh.num_vertices(); ++v) {
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(ReadLittleEndian<float>(body, &at), static_cast<float>(f.mesh.vertices[v][k]));
    }
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(ReadLittleEndian<std::uint8_t>(body, &at), f.values.rgb[v][k]);
    EXPECT_EQ(ReadLittleEndian<float>(body, &at), f.values.distance_mm[v]);
  }
  for (std::size_t t = 0; t < f.mesh.num_triangles(); ++t) {
    EXPECT_EQ(ReadLittleEndian<std::uint8_t>(body, &at), 3);
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(ReadLittleEndian<std::int32_t>(body, &at), f.mesh.triangles[t][k]);
  }
}

TEST(ColouredPlyTest, AsciiColoursAndDistancesRoundTrip) {
  const ColouredBox f;
  test::TempDir dir;
  WriteColouredPly(f.mesh, f.values, dir / "m.ply", PlyEncoding::kAscii);
  std::string body;
  HeaderLines(PlyFileBytes(dir / "m.ply"), &body);
  std::istringstream in(body);
  for (std::size_t v = 0; v < f.mesh.num_vertices(); ++v) {
    float x, y, z, d;
    int r, g, b;
    ASSERT_TRUE(in >> x >> y >> z >> r >> g >> b >> d);
    EXPECT_EQ(Eigen::Vector3d(x, y, z), f.mesh.vertices[v]);
    EXPECT_EQ(r, f.values.rgb[v][0]);
    EXPECT_EQ(g, f.values.rgb[v][1]);
    EXPECT_EQ(b, f.values.rgb[v][2]);
    EXPECT_EQ(d, f.values.distance_mm[v]);  // shortest float decimal reads back exactly
  }
  for (std::size_t t = 0; t < f.mesh.num_triangles(); ++t) {
    int n, a, b, c;
    ASSERT_TRUE(in >> n >> a >> b >> c);
    EXPECT_EQ(n, 3);
    EXPECT_EQ(Eigen::Vector3i(a, b, c), f.mesh.triangles[t]);
  }
}

TEST(ColouredPlyTest, BadValuesNameTheFileAndWriteNothing) {
  test::TempDir dir;
  const fs::path file = dir / "m.ply";
  ColouredBox short_colours;
  short_colours.values.rgb.pop_back();
  ColouredBox nan_distance;
  nan_distance.values.distance_mm[2] = std::nanf("");
  for (const ColouredBox* f : {&short_colours, &nan_distance}) {
    try {
      WriteColouredPly(f->mesh, f->values, file);
      ADD_FAILURE() << "no error";
    } catch (const MeshError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(file));
  }
  EXPECT_THROW(WriteColouredPly(ColouredBox().mesh, ColouredBox().values, dir / "no" / "m.ply"),
               MeshError);
}

}  // namespace
}  // namespace occlude::io
