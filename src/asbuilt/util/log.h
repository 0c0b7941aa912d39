#ifndef ASBUILT_UTIL_LOG_H_
#define ASBUILT_UTIL_LOG_H_

// Logging goes to stderr (stdout carries only results and, for MCP, the
// protocol). Library code logs with spdlog directly: spdlog::info(...).

namespace asbuilt {

enum class Verbosity { kQuiet, kNormal, kVerbose };

// Sends the default spdlog logger to stderr with a short pattern and sets
// its level: quiet → errors only, normal → info, verbose → debug.
void ConfigureLogging(Verbosity verbosity);

}  // namespace asbuilt

#endif  // ASBUILT_UTIL_LOG_H_
