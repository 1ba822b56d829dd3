// Fixed-size fields of the cache's byte formats (oracle_cache.cpp's entry header,
// region_entry.cpp's selection): a scalar's bytes appended, or read at an offset the caller has
// checked lies within the bytes. Native byte order: entries are read by the machine that wrote
// them.
#pragma once

#include <cstddef>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

namespace occlude::app {

template <typename T>
void PutValue(std::string* out, T value) {
  static_assert(std::is_arithmetic_v<T>, "PutValue takes scalars");
  out->append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// The T at `at`; the caller has checked at + sizeof(T) <= bytes.size().
template <typename T>
T ValueAt(std::string_view bytes, std::size_t at) {
  static_assert(std::is_arithmetic_v<T>, "ValueAt takes scalars");
  T value{};
  std::memcpy(&value, bytes.data() + at, sizeof(T));
  return value;
}

}  // namespace occlude::app
