// Private to occlude::serve: the head of an HTTP/1.x request (request line and
// headers) parsed from the bytes received so far, with the size limit applied
// before anything is parsed, and the server's fixed responses.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace occlude::app::serve_detail {

struct HttpHead {
  std::string method;  ///< e.g. "GET"
  std::string path;    ///< the target without its query
  std::size_t content_length = 0;
  std::size_t head_bytes = 0;  ///< through the blank line
};

enum class HeadStatus {
  kIncomplete,  ///< no blank line yet, within the limit
  kComplete,
  kTooLarge,  ///< the head exceeds the limit (431)
  kBad,       ///< not an HTTP/1.x request line, or a bad Content-Length (400)
};

/// Parses the head in `bytes` when it is complete within `max_bytes`.
HeadStatus ParseHttpHead(std::string_view bytes, std::size_t max_bytes, HttpHead* head);

/// A whole response that closes the connection: status line, Content-Type,
/// Content-Length, Cache-Control: no-store, Connection: close, then `body` (not for HEAD).
std::string HttpResponse(int status, std::string_view content_type, std::string_view body,
                         bool head_only = false);

/// The response head that opens an event stream (text/event-stream, no caching).
std::string EventStreamHead();

/// One server-sent event: "event: NAME", a "data: " line per line of `data`, a blank line.
std::string EventText(std::string_view event, std::string_view data);

}  // namespace occlude::app::serve_detail
