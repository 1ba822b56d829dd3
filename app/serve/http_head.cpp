// HTTP request heads and the server's responses (see http_head_internal.h).
#include <charconv>

#include "serve/http_head_internal.h"

namespace occlude::app::serve_detail {
namespace {

bool EqualsNoCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

// "METHOD SP TARGET SP HTTP/1.x".
bool ParseRequestLine(std::string_view line, HttpHead* head) {
  const std::size_t a = line.find(' ');
  const std::size_t b = a == std::string_view::npos ? a : line.find(' ', a + 1);
  if (b == std::string_view::npos || a == 0) return false;
  const std::string_view version = Trim(line.substr(b + 1));
  if (version != "HTTP/1.1" && version != "HTTP/1.0") return false;
  const std::string_view target = line.substr(a + 1, b - a - 1);
  if (target.empty() || target.front() != '/') return false;
  head->method = std::string(line.substr(0, a));
  head->path = std::string(target.substr(0, target.find('?')));
  return true;
}

}  // namespace

HeadStatus ParseHttpHead(std::string_view bytes, std::size_t max_bytes, HttpHead* head) {
  const std::size_t end = bytes.find("\r\n\r\n");
  if (end == std::string_view::npos) {
    return bytes.size() > max_bytes ? HeadStatus::kTooLarge : HeadStatus::kIncomplete;
  }
  head->head_bytes = end + 4;
  if (head->head_bytes > max_bytes) return HeadStatus::kTooLarge;
  std::string_view rest = bytes.substr(0, end + 2);
  std::size_t eol = rest.find("\r\n");
  if (!ParseRequestLine(rest.substr(0, eol), head)) return HeadStatus::kBad;
  for (rest.remove_prefix(eol + 2); !rest.empty(); rest.remove_prefix(eol + 2)) {
    eol = rest.find("\r\n");
    const std::string_view line = rest.substr(0, eol);
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos) return HeadStatus::kBad;
    if (EqualsNoCase(Trim(line.substr(0, colon)), "content-length")) {
      const std::string_view value = Trim(line.substr(colon + 1));
      const auto r =
          std::from_chars(value.data(), value.data() + value.size(), head->content_length);
      if (r.ec != std::errc() || r.ptr != value.data() + value.size()) return HeadStatus::kBad;
    }
  }
  return HeadStatus::kComplete;
}

std::string HttpResponse(int status, std::string_view content_type, std::string_view body,
                         bool head_only) {
  const char* reason = status == 200   ? "OK"
                       : status == 204 ? "No Content"
                       : status == 400 ? "Bad Request"
                       : status == 404 ? "Not Found"
                       : status == 405 ? "Method Not Allowed"
                       : status == 408 ? "Request Timeout"
                       : status == 413 ? "Payload Too Large"
                       : status == 431 ? "Request Header Fields Too Large"
                       : status == 503 ? "Service Unavailable"
                                       : "Error";
  std::string out = "HTTP/1.1 " + std::to_string(status) + " " + reason +
                    "\r\nContent-Type: " + std::string(content_type) +
                    "\r\nContent-Length: " + std::to_string(body.size()) +
                    "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n";
  if (!head_only) out += body;
  return out;
}

std::string EventStreamHead() {
  return "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\n"
         "Connection: keep-alive\r\n\r\n";
}

std::string EventText(std::string_view event, std::string_view data) {
  std::string out = "event: " + std::string(event) + "\n";
  for (;;) {
    const std::size_t eol = data.find('\n');
    std::string_view line = data.substr(0, eol);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    out += "data: " + std::string(line) + "\n";
    if (eol == std::string_view::npos) break;
    data.remove_prefix(eol + 1);
  }
  return out + "\n";
}

}  // namespace occlude::app::serve_detail
