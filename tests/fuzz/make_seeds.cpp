// Writes the fuzzers' seed corpora: small generated meshes in every flavour the
// readers accept (binary and ASCII STL, STL with a "solid" header, several
// solids; OBJ with comments, normals, texture indices, negative indices and
// polygons; ASCII and binary PLY of both endiannesses with extra properties and
// elements) and case configs using every table. Never the real scans.
// Usage: occlude_fuzz_seeds CORPUS_DIR (creates CORPUS_DIR/{stl,obj,ply,case_config}).
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "occlude/io/mesh_io.h"

namespace fs = std::filesystem;
using occlude::io::TriangleMesh;

namespace {

// A closed box [0, size]^3, 12 outward triangles.
TriangleMesh Box(double size) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) {
    m.vertices.emplace_back((i & 1) ? size : 0.0, (i & 2) ? size : 0.0, (i & 4) ? size : 0.0);
  }
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    m.triangles.emplace_back(f[0], f[1], f[2]);
    m.triangles.emplace_back(f[0], f[2], f[3]);
  }
  m.parts.push_back({"box", 0});
  m.triangle_part.assign(m.triangles.size(), 0);
  m.ComputeFaceNormals();
  return m;
}

void Put(const fs::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

std::string Read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void StlSeeds(const fs::path& dir) {
  occlude::io::WriteBinaryStl(Box(10), dir / "box-binary.stl");
  occlude::io::WriteAsciiStl(Box(10), dir / "box-ascii.stl");
  std::string solid_header = Read(dir / "box-binary.stl");
  std::memcpy(solid_header.data(), "solid box", 9);  // binary, although it starts with "solid"
  Put(dir / "box-binary-solid-header.stl", solid_header);
  const std::string facet =
      " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 10 0 0\n   vertex 0 10 0\n  "
      "endloop\n"
      " endfacet\n";
  Put(dir / "two-solids.stl",
      "solid a\n" + facet + "endsolid a\nsolid b\n" + facet + "endsolid b\n");
  Put(dir / "crlf-upper-case.stl",
      "SOLID t\r\n FACET NORMAL nan 0 1\r\n OUTER LOOP\r\n VERTEX 0 0 0\r\n VERTEX +1e1 0 0\r\n"
      " VERTEX 0 1E1 0\r\n ENDLOOP\r\n ENDFACET\r\nENDSOLID\r\n");
}

// Inputs that once broke a contract (see the regression tests in tests/io and tests/app).
void RegressionSeeds(const fs::path& stl, const fs::path& ply, const fs::path& config) {
  Put(stl / "regression-nan-cross-product.stl",
      "solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1e300 1e300 0\n"
      "   vertex 1e300 1e300 1e-300\n  endloop\n endfacet\nendsolid t\n");
  Put(ply / "regression-empty-element.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
      "z\n"
      "element junk 100000000000\nelement face 1\nproperty list uchar int "
      "vertex_indices\nend_header\n"
      "0 0 0\n10 0 0\n0 10 0\n3 0 1 2\n");
  Put(config / "regression-newline.toml", "[case]\nname = t\n\"a\\nb\" = 1\n");
}

void ObjSeeds(const fs::path& dir) {
  const TriangleMesh box = Box(10);
  std::ostringstream obj;
  obj << "# box\nmtllib box.mtl\no box\n";
  for (const auto& v : box.vertices) obj << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << "\n";
  obj << "vn 0 0 1\nvt 0 0\n";
  for (const auto& t : box.triangles)
    obj << "f " << t[0] + 1 << "/1/1 " << t[1] + 1 << "//1 " << t[2] + 1 << "\n";
  Put(dir / "box.obj", obj.str());
  Put(dir / "quad-negative.obj",
      "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0 1.0\nf -4 -3 -2 -1\ng side\ns off\nl 1 2\n");
  Put(dir / "pentagon.obj", "v 0 0 0\nv 10 0 0\nv 12 8 0\nv 5 12 0\nv -2 8 0\nf 1 2 3 4 5\n");
}

std::string PlyHeader(const std::string& format, const std::string& extra) {
  return "ply\nformat " + format +
         " 1.0\ncomment seed\nelement vertex 8\nproperty float x\nproperty float y\n"
         "property float z\n" +
         extra + "element face 12\nproperty list uchar int vertex_indices\nend_header\n";
}

void Append(std::string* out, const void* p, std::size_t n, bool big_endian) {
  const auto* b = static_cast<const char*>(p);
  for (std::size_t i = 0; i < n; ++i) *out += b[big_endian ? n - 1 - i : i];
}

std::string BinaryPly(bool big_endian) {
  const TriangleMesh box = Box(10);
  std::string ply = PlyHeader(big_endian ? "binary_big_endian" : "binary_little_endian", "");
  for (const auto& v : box.vertices) {
    for (int k = 0; k < 3; ++k) {
      const auto f = static_cast<float>(v[k]);
      Append(&ply, &f, 4, big_endian);
    }
  }
  for (const auto& t : box.triangles) {
    ply += '\3';
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = t[k];
      Append(&ply, &i, 4, big_endian);
    }
  }
  return ply;
}

void PlySeeds(const fs::path& dir) {
  const TriangleMesh box = Box(10);
  std::ostringstream ascii;
  ascii << PlyHeader("ascii", "property uchar red\n");
  for (const auto& v : box.vertices) ascii << v.x() << ' ' << v.y() << ' ' << v.z() << " 255\n";
  for (const auto& t : box.triangles) ascii << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << "\n";
  Put(dir / "box-ascii.ply", ascii.str());
  Put(dir / "box-le.ply", BinaryPly(false));
  Put(dir / "box-be.ply", BinaryPly(true));
  Put(dir / "faces-first.ply",
      "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar uint vertex_index\nelement "
      "vertex 3\n"
      "property double x\nproperty double y\nproperty double z\nelement edge 1\nproperty int "
      "vertex1\n"
      "end_header\n3 0 1 2\n0 0 0\n10 0 0\n0 10 0\n0\n");
}

void ConfigSeeds(const fs::path& dir) {
  Put(dir / "minimal.toml", "[lower]\nfile = \"lower.stl\"\n[upper]\nfile = \"upper.stl\"\n");
  Put(dir / "synthetic.toml",
      "[synthetic]\ntriangles = 5000\nseed = 3\n[output]\nfolder = \"out\"\n");
  Put(dir / "parts.toml",
      "[case]\nname = \"parts\"\nunits = \"cm\"\nup_axis = \"-z\"\n[lower]\nfile = \"lower.stl\"\n"
      "[upper]\nparts = [\"teeth/Tooth_14.stl\", \"teeth/Tooth_3.stl\"]\n");
  Put(dir / "every-table.toml",
      "[case]\nname = \"p7\"\nunits = \"mm\"\nup_axis = \"auto\"\n"
      "[lower]\nfile = \"lower.stl\"\n[upper]\nfile = \"upper.stl\"\n"
      "[accuracy]\naccuracy_mm = 0.02\nvoxel_mm = 0.25\nsample_spacing_mm = 0.2\n"
      "[contact]\nband_mm = 0.2\nmax_penetration_mm = 0.0\n"
      "[solver]\nname = \"ceres\"\nstarts = 7\nseed = 42\nthreads = 2\nproposals = 5\nmax_seconds "
      "= 12.5\n"
      "[solver.options]\nftol_rel = 1e-6\nlocal = \"ceres\"\npolish = true\nevaluations = 500\n"
      "[bounds]\ntx_mm = [-1.0, 2.0]\nrz_deg = [-4.5, 4.5]\nlocked = [\"rx\", \"ry\"]\n"
      "[start]\ntranslation_mm = [0.5, -1, 0]\nrotation_deg = [1, 2, 3]\npivot_mm = [1, 2, 3]\n"
      "[adjust]\ntranslation_mm = [0, 0, 0.1]\nrotation_deg = [0.5, 0, 0]\n"
      "[output]\nfolder = \"results/p7\"\n"
      "[report]\nmap_max_mm = 0.8\nmap_penetration_from_mm = 0.02\nimage_width_px = 800\n"
      "[limits]\nmemory_budget_mb = 1500\n");
  Put(dir / "matrix.toml",
      "[lower]\nfile = \"lower.stl\"\n[upper]\nfile = \"upper.stl\"\n"
      "[start]\nmatrix = [[1, 0, 0, 0.5], [0, 0, -1, 0], [0, 1, 0, -2], [0, 0, 0, 1]]\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: occlude_fuzz_seeds CORPUS_DIR\n";
    return 1;
  }
  const fs::path root = argv[1];
  for (const char* name : {"stl", "obj", "ply", "case_config"}) fs::create_directories(root / name);
  StlSeeds(root / "stl");
  ObjSeeds(root / "obj");
  PlySeeds(root / "ply");
  ConfigSeeds(root / "case_config");
  RegressionSeeds(root / "stl", root / "ply", root / "case_config");
  std::cout << "seeds written to " << root.string() << "\n";
  return 0;
}
