// Content hashes (content_hash.h): streaming in any pieces equals one pass, every single flipped
// bit and every appended zero byte changes the hash, and the mesh hash changes with any changed
// byte of any field while copies hash alike.
#include "occlude/io/content_hash.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <set>

#include "test_common.h"

namespace occlude::io {
namespace {

std::vector<unsigned char> RandomBytes(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<unsigned char> bytes(n);
  for (auto& b : bytes) b = static_cast<unsigned char>(rng());
  return bytes;
}

TEST(ContentHashTest, StreamingInAnyPiecesEqualsOnePass) {
  const std::vector<unsigned char> bytes = RandomBytes(1000, 1);
  std::mt19937 rng(2);
  for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{31}, std::size_t{32},
                        std::size_t{33}, std::size_t{64}, std::size_t{999}, std::size_t{1000}}) {
    const std::uint64_t whole = Hash64(bytes.data(), n, 7);
    for (int trial = 0; trial < 20; ++trial) {
      Hasher64 h(7);
      for (std::size_t done = 0; done < n;) {
        const std::size_t piece = std::min<std::size_t>(n - done, rng() % 70);
        h.Add(bytes.data() + done, piece);
        done += piece;
      }
      EXPECT_EQ(h.Finish(), whole) << n << " bytes, trial " << trial;
    }
  }
}

TEST(ContentHashTest, EveryFlippedBitAndEveryLengthChangesTheHash) {
  std::vector<unsigned char> bytes = RandomBytes(300, 3);
  const std::uint64_t original = Hash64(bytes.data(), bytes.size());
  std::set<std::uint64_t> seen{original};
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      bytes[i] ^= static_cast<unsigned char>(1u << bit);
      EXPECT_TRUE(seen.insert(Hash64(bytes.data(), bytes.size())).second) << i << ":" << bit;
      bytes[i] ^= static_cast<unsigned char>(1u << bit);
    }
  }
  // Zero bytes appended (the last stripe is zero-padded inside: the length must tell).
  std::vector<unsigned char> zeros(70, 0);
  for (std::size_t n = 0; n <= zeros.size(); ++n) {
    EXPECT_TRUE(seen.insert(Hash64(zeros.data(), n)).second) << n << " zero bytes";
  }
  EXPECT_NE(Hash64(bytes.data(), 10, 0), Hash64(bytes.data(), 10, 1)) << "the seed counts";
}

TEST(ContentHashTest, StringsAndArraysCarryTheirSizes) {
  Hasher64 a, b;
  a.AddString("ab");
  a.AddString("c");
  b.AddString("a");
  b.AddString("bc");
  EXPECT_NE(a.Finish(), b.Finish());
  Hasher64 c, d;
  c.AddArray(std::vector<int>{1, 2});
  c.AddArray(std::vector<int>{3});
  d.AddArray(std::vector<int>{1});
  d.AddArray(std::vector<int>{2, 3});
  EXPECT_NE(c.Finish(), d.Finish());
}

TEST(ContentHashTest, MeshHashChangesWithAnyFieldAndNotWithACopy) {
  TriangleMesh mesh = test::MakeSphere({1, 2, 3}, 2.0, 6, 8);
  mesh.parts[0].tooth_number = 14;
  const std::uint64_t original = MeshContentHash(mesh);
  EXPECT_EQ(MeshContentHash(TriangleMesh(mesh)), original);
  std::vector<std::pair<std::string, TriangleMesh>> changed;
  changed.reserve(16);  // variant() hands out references into it
  auto variant = [&](const std::string& what) -> TriangleMesh& {
    changed.emplace_back(what, mesh);
    return changed.back().second;
  };
  {
    TriangleMesh& m = variant("lowest bit of one coordinate");
    std::uint64_t bits;
    std::memcpy(&bits, &m.vertices[5].y(), sizeof bits);
    bits ^= 1;
    std::memcpy(&m.vertices[5].y(), &bits, sizeof bits);
  }
  variant("a triangle's corner order").triangles[3] = mesh.triangles[3].reverse();
  variant("a face normal").face_normals[2].x() += 1e-12;
  variant("a triangle's part").triangle_part[1] = 1;
  variant("a tooth number").parts[0].tooth_number = 15;
  variant("a part name").parts[0].name += "x";
  variant("one more part").parts.push_back(MeshPart{"gingiva", 0});
  variant("one triangle fewer").triangles.pop_back();
  {
    TriangleMesh& m = variant("-0 instead of +0");
    m.vertices.push_back(Eigen::Vector3d(0.0, 0.0, 0.0));
    TriangleMesh& n = variant("+0");
    n.vertices.push_back(Eigen::Vector3d(-0.0, 0.0, 0.0));
  }
  std::set<std::uint64_t> seen{original};
  for (const auto& [what, m] : changed) {
    EXPECT_TRUE(seen.insert(MeshContentHash(m)).second) << what;
  }
}

TEST(ContentHashTest, HexIsSixteenLowerCaseDigits) {
  EXPECT_EQ(HashHex(0), "0000000000000000");
  EXPECT_EQ(HashHex(0x0123456789abcdefULL), "0123456789abcdef");
  EXPECT_EQ(HashHex(~std::uint64_t{0}), "ffffffffffffffff");
}

}  // namespace
}  // namespace occlude::io
