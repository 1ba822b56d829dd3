// Private to occlude::collision: the byte writer and the bounds-checked byte reader that the
// saved-oracle codec (oracle_codec.cpp) writes and reads structures with. Scalars and arrays of
// plain values travel as their bytes (little-endian machines only, as content_hash.h); an
// array is its u64 element count, then its elements.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "occlude/collision/oracle_file.h"

namespace occlude::collision::detail {

/// Types whose bytes are their value: trivially copyable ones and fixed-size Eigen matrices of
/// scalars (whose bytes are the coefficients, without padding).
template <typename T>
struct IsBytes : std::is_trivially_copyable<T> {};
template <typename S, int R, int C, int O, int MR, int MC>
struct IsBytes<Eigen::Matrix<S, R, C, O, MR, MC>>
    : std::bool_constant<std::is_arithmetic_v<S> && R != Eigen::Dynamic && C != Eigen::Dynamic &&
                         sizeof(Eigen::Matrix<S, R, C, O, MR, MC>) == sizeof(S) * R * C> {};

/// Where a ByteWriter's bytes go: a sink that takes them in order, in pieces of any size.
using ByteSink = std::function<void(std::string_view)>;

/// Writes values to a ByteSink in pieces: small values gathered in a buffer of about
/// kPieceBytes, large arrays handed over from their own memory, so that nothing of the size of
/// what is written is held. Flush() hands over what the buffer holds (a sink's writer needs
/// it once it is done).
class ByteWriter {
 public:
  static constexpr std::size_t kPieceBytes = std::size_t{1} << 20;

  explicit ByteWriter(const ByteSink* sink) : sink_(*sink) {}

  template <typename T>
  void Value(const T& value) {
    static_assert(IsBytes<T>::value, "Value writes plain values");
    Put(reinterpret_cast<const char*>(&value), sizeof(T));
  }
  template <typename T>
  void Array(const std::vector<T>& values) {
    static_assert(IsBytes<T>::value, "Array writes arrays of plain values");
    Value(static_cast<std::uint64_t>(values.size()));
    Put(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  /// One byte (0 or 1) per element.
  void Bools(const std::vector<bool>& values) {
    Array(std::vector<std::uint8_t>(values.begin(), values.end()));
  }
  void Flush() {
    if (buffer_.empty()) return;
    sink_(buffer_);
    buffer_.clear();
  }

 private:
  void Put(const char* data, std::size_t size) {
    if (size >= kPieceBytes) {
      Flush();
      sink_(std::string_view(data, size));
    } else {
      buffer_.append(data, size);
      if (buffer_.size() >= kPieceBytes) Flush();
    }
  }

  const ByteSink& sink_;
  std::string buffer_;
};

/// Reads what a ByteWriter wrote; any read past the end, or an array longer than the bytes
/// left, throws OracleFileError(kCorrupt) naming the section.
/// Called with the bytes an array was copied out of, when the reader's source may let them go
/// (a file mapping drops its pages: the run does not hold a file and its copy at once).
using ReleaseBytes = std::function<void(const char* data, std::size_t size)>;

class ByteReader {
 public:
  ByteReader(std::string_view bytes, std::string section, const ReleaseBytes* release = nullptr)
      : bytes_(bytes), section_(std::move(section)), release_(release) {}

  template <typename T>
  T Value() {
    static_assert(IsBytes<T>::value, "Value reads plain values");
    Need(sizeof(T));
    T value{};
    std::memcpy(static_cast<void*>(&value), bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  template <typename T>
  void Array(std::vector<T>* values) {
    static_assert(IsBytes<T>::value, "Array reads arrays of plain values");
    const auto count = Value<std::uint64_t>();
    if (count > (bytes_.size() - at_) / sizeof(T)) Fail("an array is longer than the section");
    values->resize(static_cast<std::size_t>(count));
    if (values->empty()) return;  // data() may be null: no memcpy of nothing from it
    std::memcpy(static_cast<void*>(values->data()), bytes_.data() + at_,
                values->size() * sizeof(T));
    if (release_ != nullptr && *release_)
      (*release_)(bytes_.data() + at_, values->size() * sizeof(T));
    at_ += values->size() * sizeof(T);
  }
  /// An Array of `expected` elements (else kCorrupt: the sizes disagree).
  template <typename T>
  void ArrayOf(std::size_t expected, std::vector<T>* values) {
    Array(values);
    if (values->size() != expected) Fail("an array's size disagrees with the structure's");
  }
  void Bools(std::vector<bool>* values) {
    std::vector<std::uint8_t> bytes;
    Array(&bytes);
    values->assign(bytes.begin(), bytes.end());
  }
  /// Throws kCorrupt unless `condition` (a consistency check of what was read).
  void Check(bool condition, const char* what) const {
    if (!condition) Fail(what);
  }
  bool done() const { return at_ == bytes_.size(); }
  [[noreturn]] void Fail(const std::string& what) const {
    throw OracleFileError(OracleFileProblem::kCorrupt, "section " + section_ + ": " + what);
  }

 private:
  void Need(std::size_t n) const {
    if (n > bytes_.size() - at_) Fail("ends early");
  }
  std::string_view bytes_;
  std::string section_;
  const ReleaseBytes* release_;
  std::size_t at_ = 0;
};

}  // namespace occlude::collision::detail
