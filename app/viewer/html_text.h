// Text for self-contained HTML: base64 of bytes (data URIs, embedded typed
// arrays), HTML escaping of text and attributes, and JSON made safe to sit
// inside a <script> element. The report's pages embed their images with this Base64.
#pragma once

#include <string>
#include <string_view>

namespace occlude::app {

/// Standard base64 (RFC 4648, '+' '/', '=' padding, no line breaks).
std::string Base64(std::string_view bytes);

/// `text` with & < > " ' replaced by entities, for element text and attribute values.
std::string HtmlEscape(std::string_view text);

/// JSON text with every '<' written as \u003c, so no "</script>" or "<!--" can end
/// or confuse the element it is embedded in; still the same JSON value.
std::string ScriptSafeJson(std::string_view json);

}  // namespace occlude::app
