// A corpus of broken mesh files, generated here: each must be rejected with a
// one-line MeshError that starts with the file path and names the problem,
// without crashing, hanging or allocating by a count the file does not back.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

#include "occlude/io/mesh_io.h"
#include "test_common.h"

namespace occlude::io {
namespace {

namespace fs = std::filesystem;

class BrokenFileTest : public ::testing::Test {
 protected:
  fs::path Write(const std::string& name, const std::string& bytes) {
    const fs::path file = dir_ / name;
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
  }

  // A valid 12-triangle binary STL box, as bytes.
  std::string BoxStl() {
    WriteBinaryStl(test::MakeBox({0, 0, 0}, {10, 10, 10}), dir_ / "box-source.stl");
    std::ifstream in(dir_ / "box-source.stl", std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  static std::string WithCount(std::string stl, std::uint32_t count) {
    std::memcpy(stl.data() + 80, &count, 4);  // little-endian host
    return stl;
  }

  // A one-facet ASCII STL whose second vertex line is `vertex`.
  static std::string AsciiFacet(const std::string& vertex) {
    return "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   " + vertex +
           "\n   vertex 0 10 0\n  endloop\n endfacet\nendsolid t\n";
  }

  static void ExpectRejected(const fs::path& file, const std::string& phrase) {
    try {
      const TriangleMesh mesh = LoadMesh(file);
      ADD_FAILURE() << file << " was accepted with " << mesh.num_triangles() << " triangles";
    } catch (const MeshError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
      EXPECT_NE(message.find(phrase), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }

  test::TempDir dir_;
};

TEST_F(BrokenFileTest, MissingFile) { ExpectRejected(dir_ / "nothing.stl", "no such file"); }

TEST_F(BrokenFileTest, Directory) {
  fs::create_directory(dir_ / "folder.stl");
  ExpectRejected(dir_ / "folder.stl", "is a folder");
}

TEST_F(BrokenFileTest, EmptyFile) { ExpectRejected(Write("empty.stl", ""), "empty (0 bytes)"); }

// As root (which reads any file) the load runs in a child switched to the user nobody.
TEST_F(BrokenFileTest, UnreadableFile) {
  const fs::path file = Write("secret.stl", BoxStl());
  fs::permissions(file, fs::perms::none);
  fs::permissions(dir_.path(), fs::perms::owner_all | fs::perms::group_read |
                                   fs::perms::group_exec | fs::perms::others_read |
                                   fs::perms::others_exec);
  std::string why;
  const auto message = test::RunUnprivileged(
      [&] {
        try {
          LoadMesh(file);
          return std::string("accepted");
        } catch (const MeshError& e) {
          return std::string(e.what());
        }
      },
      &why);
  if (!message) GTEST_SKIP() << "cannot run as an unprivileged user: " << why;
  EXPECT_EQ(message->rfind(file.string() + ": ", 0), 0u) << *message;
  EXPECT_NE(message->find("Permission denied"), std::string::npos) << *message;
  EXPECT_NE(message->find("check the file's permissions"), std::string::npos) << *message;
}

TEST_F(BrokenFileTest, LoadMeshFromBytesMatchesTheFile) {
  const std::string stl = BoxStl();
  const TriangleMesh from_file = LoadMesh(Write("box.stl", stl));
  const TriangleMesh from_bytes = LoadMeshFromBytes(stl, "memory/box.stl");
  EXPECT_EQ(from_file.vertices, from_bytes.vertices);
  EXPECT_EQ(from_file.triangles, from_bytes.triangles);
  EXPECT_EQ(from_bytes.parts.front().name, "box");
  try {
    LoadMeshFromBytes(stl.substr(0, 100), "memory/cut.stl");
    ADD_FAILURE() << "a truncated STL was accepted";
  } catch (const MeshError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("memory/cut.stl: ", 0), 0u) << e.what();
  }
  EXPECT_THROW(LoadMeshFromBytes("", "memory/empty.stl"), MeshError);
}

TEST_F(BrokenFileTest, UnsupportedExtension) {
  ExpectRejected(Write("box.3mf", BoxStl()), "unsupported file type '.3mf'");
  ExpectRejected(Write("box", BoxStl()), "has no file extension");
}

TEST_F(BrokenFileTest, TruncatedBinaryStl) {
  const std::string stl = BoxStl();
  ExpectRejected(Write("cut.stl", stl.substr(0, stl.size() - 20)),
                 "header says 12 triangles, which needs 684 bytes, but the file has 664 bytes; "
                 "the file is truncated");
}

TEST_F(BrokenFileTest, BinaryStlCutInsideTheHeader) {
  ExpectRejected(Write("header.stl", BoxStl().substr(0, 60)), "shorter than a binary STL header");
}

TEST_F(BrokenFileTest, BinaryStlWithWrongCount) {
  ExpectRejected(Write("count.stl", WithCount(BoxStl(), 5)),
                 "the size fits 12 triangles, so the header count is wrong");
}

TEST_F(BrokenFileTest, BinaryStlClaimingFourBillionTriangles) {
  ExpectRejected(Write("huge.stl", WithCount(BoxStl(), 4000000000u)),
                 "header says 4000000000 triangles, which needs 200000000084 bytes, but the file "
                 "has 684 bytes");
}

TEST_F(BrokenFileTest, BinaryStlWithZeroTriangles) {
  ExpectRejected(Write("zero.stl", WithCount(BoxStl().substr(0, 84), 0)), "no triangles");
}

TEST_F(BrokenFileTest, BinaryStlWithNaNCoordinate) {
  std::string stl = BoxStl();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(stl.data() + 84 + 50 * 3 + 12 + 4, &nan, 4);  // triangle 4, vertex 1, y
  ExpectRejected(Write("nan.stl", stl), "triangle 4 of 12 has a non-finite vertex coordinate");
}

TEST_F(BrokenFileTest, GarbageBytes) {
  std::mt19937 random(42);
  std::string bytes(1000, '\0');
  for (char& c : bytes) c = static_cast<char>(random());
  ExpectRejected(Write("garbage.stl", bytes), "not an STL file");
  ExpectRejected(Write("garbage.obj", bytes), "binary data");
  ExpectRejected(Write("garbage.ply", bytes), "not a PLY file");
}

TEST_F(BrokenFileTest, TextFileIsNotAMesh) {
  const std::string text = "Dear colleague,\nplease find the scans attached.\n";
  ExpectRejected(Write("letter.stl", text), "not an STL file: it is text");
  ExpectRejected(Write("letter.obj", text), "not an OBJ mesh");
  ExpectRejected(Write("letter.ply", text), "not a PLY file");
}

TEST_F(BrokenFileTest, AsciiStlWithNaN) {
  ExpectRejected(Write("nan.stl", AsciiFacet("vertex 10 nan 0")),
                 "line 5: non-finite vertex coordinate 'nan' in facet 1");
}

TEST_F(BrokenFileTest, AsciiStlWithInfinity) {
  ExpectRejected(Write("inf.stl", AsciiFacet("vertex -inf 0 0")),
                 "non-finite vertex coordinate '-inf'");
}

// Regression (fuzz_stl's contract): corners of 1e300 mm made the cross product
// inf - inf = NaN, so the triangle was neither dropped as degenerate nor usable.
TEST_F(BrokenFileTest, AsciiStlWithAbsurdCoordinates) {
  ExpectRejected(Write("big.stl",
                       "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                       "   vertex 1e300 1e300 0\n   vertex 1e300 1e300 1e-300\n  endloop\n"
                       " endfacet\nendsolid t\n"),
                 "a vertex coordinate of 1e+300 mm is beyond the +-1e15 mm");
  // In metres, 1e13 m is 1e16 mm: also beyond.
  try {
    LoadOptions metres;
    metres.unit = LengthUnit::kMetre;
    LoadMesh(Write("far.stl", AsciiFacet("vertex 1e13 0 0")), metres);
    ADD_FAILURE() << "accepted";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("1e+16 mm"), std::string::npos) << e.what();
  }
}

TEST_F(BrokenFileTest, AsciiStlWithGarbageToken) {
  ExpectRejected(Write("abc.stl", AsciiFacet("vertex 10 abc 0")),
                 "line 5: 'abc' is not a number (vertex coordinate in facet 1)");
  ExpectRejected(Write("comma.stl", AsciiFacet("vertex 10 0,5 0")), "'0,5' is not a number");
}

TEST_F(BrokenFileTest, AsciiStlMissingEndloop) {
  std::string text = AsciiFacet("vertex 10 0 0");
  text.erase(text.find("  endloop\n"), 10);
  ExpectRejected(Write("endloop.stl", text), "expected 'endloop' in facet 1, found 'endfacet'");
}

TEST_F(BrokenFileTest, AsciiStlMissingEndfacet) {
  std::string text = AsciiFacet("vertex 10 0 0");
  text.erase(text.find(" endfacet\n"), 10);
  ExpectRejected(Write("endfacet.stl", text), "expected 'endfacet' in facet 1, found 'endsolid'");
}

TEST_F(BrokenFileTest, TruncatedAsciiStl) {
  const std::string text = AsciiFacet("vertex 10 0 0");
  ExpectRejected(Write("cut1.stl", text.substr(0, text.find("vertex 0 10"))),
                 "the file ends inside facet 1 where 'vertex' was expected");
  ExpectRejected(Write("cut2.stl", text.substr(0, text.find("endsolid"))),
                 "the file ends without 'endsolid'");
}

TEST_F(BrokenFileTest, AsciiStlWithFourVertices) {
  std::string text = AsciiFacet("vertex 10 0 0");
  text.insert(text.find("  endloop"), "   vertex 5 5 5\n");
  ExpectRejected(Write("quad.stl", text), "expected 'endloop' in facet 1, found 'vertex'");
}

TEST_F(BrokenFileTest, OnlyDegenerateTriangles) {
  TriangleMesh flat;
  flat.vertices = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  flat.triangles = {{0, 1, 2}, {0, 0, 1}};
  WriteBinaryStl(flat, dir_ / "flat.stl");
  ExpectRejected(dir_ / "flat.stl", "all 2 triangles are degenerate");
}

TEST_F(BrokenFileTest, ObjIndexOutOfRange) {
  ExpectRejected(Write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 7\n"),
                 "line 5: a face refers to vertex 7 but the file has only 3 vertices");
  ExpectRejected(Write("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"),
                 "line 4: relative index -4 reaches before the first vertex");
  ExpectRejected(Write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
                 "'0' is not a vertex index");
}

TEST_F(BrokenFileTest, ObjWithBadNumbers) {
  ExpectRejected(Write("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"),
                 "line 2: non-finite vertex coordinate 'nan'");
  ExpectRejected(Write("abc.obj", "v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n"),
                 "line 2: 'abc' is not a number");
  ExpectRejected(Write("short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n"),
                 "line 2: 'v' needs 3 coordinates");
  ExpectRejected(Write("line.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"),
                 "a face needs at least 3 vertices");
}

TEST_F(BrokenFileTest, ObjPointCloud) {
  ExpectRejected(Write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "contains no faces");
}

const char* const kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

TEST_F(BrokenFileTest, PlyIndexOutOfRange) {
  ExpectRejected(Write("range.ply", std::string(kPlyHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n"),
                 "line 13: face 0 refers to vertex 9, but the file has only 3 vertices");
  ExpectRejected(Write("quad.ply", std::string(kPlyHeader) + "0 0 0\n1 0 0\n0 1 0\n4 0 1 2 3\n"),
                 "refers to vertex 3");
}

TEST_F(BrokenFileTest, PlyWithNaNAndGarbage) {
  ExpectRejected(Write("nan.ply", std::string(kPlyHeader) + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"),
                 "line 11: vertex 1 has a non-finite coordinate");
  ExpectRejected(Write("abc.ply", std::string(kPlyHeader) + "0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n"),
                 "line 11: 'abc' is not a number (property 'y' of vertex 1)");
}

TEST_F(BrokenFileTest, PlyWithoutProperCoordinates) {
  std::string ply = kPlyHeader;
  ply.replace(ply.find("property float y"), 16, "property float x");
  ExpectRejected(Write("twice.ply", ply + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                 "properties x, y and z once each");
}

TEST_F(BrokenFileTest, PlyClaimingHugeCounts) {
  std::string header = kPlyHeader;
  header.replace(header.find("vertex 3"), 8, "vertex 4000000000");
  header.replace(header.find("face 1"), 6, "face 4000000000");
  ExpectRejected(Write("huge.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                 "the PLY ends inside vertex 4 of 4000000000, so it is truncated");
  std::string binary = header;
  binary.replace(binary.find("ascii"), 5, "binary_little_endian");
  ExpectRejected(Write("huge-binary.ply", binary + std::string(40, '\0')),
                 "ends inside vertex 3 of 4000000000");  // 40 bytes = 3 vertices + 4 bytes
}

// Regression: an element without properties but with a count of 10^11 made the
// body walk spin for hours (each item reads nothing, so the end is never reached).
TEST_F(BrokenFileTest, PlyElementWithoutPropertiesAndHugeCountIsSkipped) {
  std::string ply = kPlyHeader;
  ply.insert(ply.find("element face"), "element junk 100000000000\n");
  const TriangleMesh mesh = LoadMesh(Write("junk.ply", ply + "0 0 0\n10 0 0\n0 10 0\n3 0 1 2\n"));
  EXPECT_EQ(mesh.num_triangles(), 1u);
}

TEST_F(BrokenFileTest, TruncatedBinaryPly) {
  std::string ply = kPlyHeader;
  ply.replace(ply.find("ascii"), 5, "binary_little_endian");
  ply += std::string(36, '\0');                        // the three vertices
  ply += std::string(1, '\3') + std::string(6, '\0');  // a face cut after 1.5 indices
  ExpectRejected(Write("cut.ply", ply), "the PLY ends inside face 0 of 1");
}

TEST_F(BrokenFileTest, PlyWithoutFaces) {
  std::string ply = kPlyHeader;
  ply.replace(ply.find("face 1"), 6, "face 0");
  ExpectRejected(Write("cloud.ply", ply + "0 0 0\n1 0 0\n0 1 0\n"), "contains no faces");
}

TEST_F(BrokenFileTest, PlyWithoutEndHeader) {
  ExpectRejected(Write("open.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"),
                 "no 'end_header' line");
}

}  // namespace
}  // namespace occlude::io
