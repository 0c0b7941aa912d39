#include "asbuilt/util/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace asbuilt {

void ConfigureLogging(Verbosity verbosity) {
  static bool configured = false;
  if (!configured) {
    auto logger = spdlog::stderr_color_mt("asbuilt");
    logger->set_pattern("%^%l%$: %v");
    spdlog::set_default_logger(logger);
    configured = true;
  }
  switch (verbosity) {
    case Verbosity::kQuiet:
      spdlog::set_level(spdlog::level::err);
      break;
    case Verbosity::kNormal:
      spdlog::set_level(spdlog::level::info);
      break;
    case Verbosity::kVerbose:
      spdlog::set_level(spdlog::level::debug);
      break;
  }
}

}  // namespace asbuilt
