// Open-addressing hash from 64-bit keys to 32-bit values, shared by the
// sparse brick structures (narrow-band distance field, distance bound).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "occlude/io/content_hash.h"

namespace occlude::collision::detail {

/// Writes and reads the built structures (oracle_file.h); a friend of the classes it saves.
struct OracleCodec;

/// Open-addressing hash from a 64-bit key (never ~0) to a 32-bit value:
/// power-of-two capacity, load <= 3/4, linear probing, splitmix64 finaliser.
class KeyIndexHash {
 public:
  static constexpr std::uint32_t kNotFound = 0xffffffffu;
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

  /// Empties the table and sizes it for `n` keys.
  void Reset(std::size_t n);
  /// Value of `key`, inserting `value` when absent; *inserted says which.
  std::uint32_t Insert(std::uint64_t key, std::uint32_t value, bool* inserted);
  /// Value of `key` or kNotFound.
  std::uint32_t Find(std::uint64_t key) const {
    if (slots_.empty()) return kNotFound;
    for (std::size_t i = Mix(key) & mask_;; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.key == key) return s.value;
      if (s.key == kEmpty) return kNotFound;
    }
  }
  std::size_t size() const { return size_; }
  std::size_t MemoryBytes() const { return slots_.capacity() * sizeof(Slot); }

  static std::uint64_t Mix(std::uint64_t x) { return io::Mix64(x); }

 private:
  friend struct OracleCodec;
  struct Slot {
    std::uint64_t key = kEmpty;
    std::uint32_t value = 0;
  };
  std::vector<Slot> slots_;
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

}  // namespace occlude::collision::detail
