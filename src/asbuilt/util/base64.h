#ifndef ASBUILT_UTIL_BASE64_H_
#define ASBUILT_UTIL_BASE64_H_

// Standard base64 (RFC 4648, with padding): inline images in the HTML
// report, image content in MCP replies.

#include <string>
#include <string_view>

namespace asbuilt {

std::string Base64Encode(std::string_view bytes);

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_BASE64_H_
