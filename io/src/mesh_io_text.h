// Private to occlude::io: small text-scanning helpers shared by the ASCII STL
// reader and the OBJ/PLY pre-checks. Locale-independent (std::from_chars).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace occlude::io::detail {

bool IsSpace(char c);
bool EqualsNoCase(std::string_view a, std::string_view b);
bool StartsWithNoCase(std::string_view text, std::string_view prefix);

/// Parses a whole token as a real number ("1", "+2.5", "-3e-4", "nan", "inf");
/// false when any character is left over or nothing parses.
bool ParseReal(std::string_view token, double* value);
/// Parses a whole token as a decimal integer with optional sign.
bool ParseInt(std::string_view token, long long* value);

/// The shortest decimal that reads back as `value` ("9", "0.1", "1e-05").
std::string FormatNumber(double value);

/// A token for an error message: quoted, at most 24 characters, bytes that are
/// not printable ASCII shown as '?'.
std::string Quote(std::string_view token);

/// `text` without a leading UTF-8 byte-order mark.
std::string_view WithoutUtf8Bom(std::string_view text);

/// Splits off the first whitespace-separated token of `*rest` (empty when none).
std::string_view PopToken(std::string_view* rest);

/// Whitespace-separated tokens of a text, with 1-based line numbers.
class Tokenizer {
 public:
  explicit Tokenizer(std::string_view text) : text_(text) {}
  /// The next token, empty at the end of the text; line() is then its line.
  std::string_view Next();
  /// Skips to the start of the next line.
  void SkipRestOfLine();
  int line() const { return line_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

/// Lines of a text ('\n' or "\r\n" terminated, the last one may be unterminated).
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}
  /// The next line without its terminator; false at the end of the text.
  bool Next(std::string_view* line);
  /// 1-based number of the line last returned.
  int line_number() const { return line_number_; }
  /// Bytes consumed so far (terminators included).
  std::size_t offset() const { return pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_number_ = 0;
};

}  // namespace occlude::io::detail
