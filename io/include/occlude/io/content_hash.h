// Content hashes: a fast 64-bit hash of bytes (for checksums of saved files and for cache
// keys) and the content hash of a TriangleMesh (every field, bit-exact).
//
// Not cryptographic: it detects accidental change (a truncated or torn file, a flipped bit, an
// edited mesh), not a forgery. Any change of a single 8-byte word of the input changes every
// lane's state for good (each step is a bijection of the state for a fixed word and of the
// word for a fixed state), so it always changes the 256-bit state before the final fold into
// 64 bits; the fold is a good mix (multiplications and xor-shifts), so other changes collide
// with probability about 2^-64. Deterministic across runs and machines of one byte order (the
// project targets little-endian x86-64 and AArch64).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "occlude/io/triangle_mesh.h"

namespace occlude::io {

/// The splitmix64 finaliser: a bijective avalanche of 64 bits (every output bit depends on
/// every input bit).
inline std::uint64_t Mix64(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

/// Streaming 64-bit hash: Add() any byte sequence in any pieces, Finish() gives the same value
/// as one Add() of the concatenation. About 8-10 GB/s (four independent lanes of 8-byte words).
class Hasher64 {
 public:
  explicit Hasher64(std::uint64_t seed = 0);

  void Add(const void* data, std::size_t size);
  /// A scalar's bytes.
  template <typename T>
  void AddValue(const T& value) {
    static_assert(std::is_arithmetic_v<T>, "AddValue takes scalars (structs may hold padding)");
    Add(&value, sizeof(T));
  }
  /// A string's length, then its bytes (so that ("ab", "c") and ("a", "bc") differ).
  void AddString(std::string_view text);
  /// An array's element count, then its bytes. T: scalars or fixed-size Eigen vectors of
  /// them, whose bytes hold no padding (so every byte hashed is a value's).
  template <typename T>
  void AddArray(const std::vector<T>& values) {
    AddValue(static_cast<std::uint64_t>(values.size()));
    Add(values.data(), values.size() * sizeof(T));
  }

  /// The hash of everything added (the hasher may go on being fed afterwards).
  std::uint64_t Finish() const;

 private:
  void Stripe(const unsigned char* p);  ///< one 32-byte stripe into the four lanes

  std::array<std::uint64_t, 4> lane_{};
  std::array<unsigned char, 32> pending_{};  ///< bytes not yet forming a whole stripe
  std::size_t pending_size_ = 0;
  std::uint64_t length_ = 0;
  std::uint64_t seed_;
};

/// Hash64 of one byte range (Hasher64 with `seed`).
std::uint64_t Hash64(const void* data, std::size_t size, std::uint64_t seed = 0);

/// Content hash of a mesh: vertices, triangles, face normals, per-triangle parts and the parts
/// (names and tooth numbers), each with its size, bit-exact (so -0.0 and +0.0 differ, and any
/// changed byte of a coordinate changes the hash). Two meshes with the same hash build the
/// same structures.
std::uint64_t MeshContentHash(const TriangleMesh& mesh);

/// `value` as 16 lower-case hexadecimal digits (a file-name-safe key).
std::string HashHex(std::uint64_t value);

}  // namespace occlude::io
