// Fuzzes the scene JSON reader: parse, validate, and — for anything that
// reads — write and read back to the same JSON (round trip).
#include <cstdint>
#include <string_view>

#include "asbuilt/scene/scene_json.h"
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
    asbuilt::Scene scene = asbuilt::SceneFromJson(doc, "fuzz.json");
    nlohmann::json out = asbuilt::SceneToJson(scene);
    asbuilt::Scene back = asbuilt::SceneFromJson(out, "roundtrip");
    if (asbuilt::SceneToJson(back) != out) __builtin_trap();
    (void)asbuilt::SceneTruth(scene);
    (void)asbuilt::DescribeScene(scene);
  } catch (const asbuilt::InputError&) {
  }
  return 0;
}
