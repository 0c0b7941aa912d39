// Fuzzes the labelled point file reader.
#include <cstdint>
#include <string_view>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)asbuilt::ParsePoints(text, "fuzz.txt");
  } catch (const asbuilt::InputError&) {
  }
  return 0;
}
