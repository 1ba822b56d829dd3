// Text-scanning helpers for the mesh readers (tokens, lines, numbers).
#include "mesh_io_text.h"

#include <charconv>

namespace occlude::io::detail {
namespace {

char Lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

// std::from_chars rejects a leading '+'; files written by some exporters have it.
std::string_view WithoutPlus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  return token;
}

}  // namespace

bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

bool EqualsNoCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (Lower(a[i]) != Lower(b[i])) return false;
  }
  return true;
}

bool StartsWithNoCase(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() && EqualsNoCase(text.substr(0, prefix.size()), prefix);
}

bool ParseReal(std::string_view token, double* value) {
  token = WithoutPlus(token);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  // Out-of-range values are garbage too (from_chars leaves *value untouched).
  return ec == std::errc() && ptr == end;
}

bool ParseInt(std::string_view token, long long* value) {
  token = WithoutPlus(token);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end;
}

std::string FormatNumber(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string Quote(std::string_view token) {
  constexpr std::size_t kMaxChars = 24;
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < kMaxChars; ++i) {
    const char c = token[i];
    out += (c >= 0x20 && c < 0x7f) ? c : '?';
  }
  if (token.size() > kMaxChars) out += "...";
  return out + "'";
}

std::string_view WithoutUtf8Bom(std::string_view text) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (text.substr(0, kBom.size()) == kBom) text.remove_prefix(kBom.size());
  return text;
}

std::string_view PopToken(std::string_view* rest) {
  std::size_t begin = 0;
  while (begin < rest->size() && IsSpace((*rest)[begin])) ++begin;
  std::size_t end = begin;
  while (end < rest->size() && !IsSpace((*rest)[end])) ++end;
  const std::string_view token = rest->substr(begin, end - begin);
  rest->remove_prefix(end);
  return token;
}

std::string_view Tokenizer::Next() {
  while (pos_ < text_.size() && IsSpace(text_[pos_])) {
    if (text_[pos_] == '\n') ++line_;
    ++pos_;
  }
  const std::size_t begin = pos_;
  while (pos_ < text_.size() && !IsSpace(text_[pos_])) ++pos_;
  return text_.substr(begin, pos_ - begin);
}

void Tokenizer::SkipRestOfLine() {
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
}

bool LineReader::Next(std::string_view* line) {
  if (pos_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  std::string_view found = text_.substr(pos_, end - pos_);
  if (!found.empty() && found.back() == '\r') found.remove_suffix(1);
  pos_ = end < text_.size() ? end + 1 : end;
  ++line_number_;
  *line = found;
  return true;
}

}  // namespace occlude::io::detail
