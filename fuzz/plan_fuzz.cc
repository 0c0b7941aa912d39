// Fuzzes the plan.json / truth.json reader and writer.
#include <cstdint>
#include <string_view>

#include "asbuilt/formats/plan_file.h"
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
    asbuilt::Plan plan = asbuilt::PlanFromJson(doc, "fuzz.json");
    // Whatever reads must write and read back.
    asbuilt::Plan back = asbuilt::PlanFromJson(asbuilt::PlanToJson(plan), "roundtrip");
    if (back.walls.size() != plan.walls.size()) __builtin_trap();
  } catch (const asbuilt::InputError&) {
  }
  return 0;
}
