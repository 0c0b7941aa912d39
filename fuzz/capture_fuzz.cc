// Fuzzes the capture.json reader (JSON parse + validation).
#include <cstdint>
#include <string_view>

#include "asbuilt/formats/capture.h"
#include "asbuilt/util/json_reader.h"
#include "asbuilt/util/log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static bool init = (asbuilt::ConfigureLogging(asbuilt::Verbosity::kQuiet), true);
  (void)init;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  asbuilt::JsonDiagnostics diag("fuzz.json");
  nlohmann::json doc = asbuilt::ParseJsonText(text, diag);
  if (!diag.ok()) return 0;
  try {
    asbuilt::Capture c = asbuilt::CaptureFromJson(doc, "fuzz.json", "/nonexistent-fuzz-dir");
    (void)asbuilt::CaptureToJson(c).dump();
  } catch (const asbuilt::InputError&) {
  }
  return 0;
}
