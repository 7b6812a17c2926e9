#pragma once
// Base64 (RFC 4648 §4, the standard alphabet with `=` padding): how report.html embeds its
// figures as `data:image/png;base64,...` URIs.

#include <string>
#include <string_view>

namespace retrace::bench {

/// The Base64 encoding of `bytes`: 4 characters per 3 bytes, padded with `=`, no line breaks.
std::string Base64Encode(std::string_view bytes);

}  // namespace retrace::bench
