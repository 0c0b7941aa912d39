// Fuzzes the built-in text parser: any text gives a valid scene or
// asbuilt's own error, never a crash.
#include <cstdint>
#include <string_view>

#include "asbuilt/scene/scene_text.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static bool init = (asbuilt::ConfigureLogging(asbuilt::Verbosity::kQuiet), true);
  (void)init;
  if (size > 4096) return 0;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    asbuilt::SceneTextResult r = asbuilt::SceneFromText(text);
    if (!asbuilt::ValidateScene(r.scene).empty()) __builtin_trap();  // Promised valid.
  } catch (const asbuilt::Error&) {
  }
  return 0;
}
