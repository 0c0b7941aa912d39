#ifndef ASBUILT_UTIL_TEXT_H_
#define ASBUILT_UTIL_TEXT_H_

// Small text helpers shared by the readers.

#include <string>
#include <string_view>

namespace asbuilt {

// `s` with A–Z turned to a–z (bytes of other scripts left as they are): for
// file extensions and keywords, ".PNG" → ".png".
std::string AsciiLower(std::string_view s);

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_TEXT_H_
