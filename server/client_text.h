// Text a client sent, made safe to put in a status message or a log line:
// control bytes and quotes escaped, so a name cannot forge a log line, and
// cut short, so a 4 MiB name costs neither log volume nor trailer space.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace scallop::server {

// `text` in single quotes, bytes outside printable ASCII as \xNN and the
// quote and backslash escaped; beyond `max_bytes` of input, cut there and
// followed by "... (N bytes)". The result is printable ASCII with no
// newline, at most 4 * max_bytes + 40 bytes. O(min(size, max_bytes)).
std::string QuotedClientText(std::string_view text, size_t max_bytes = 64);

}  // namespace scallop::server
