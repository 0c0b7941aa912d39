#ifndef ASBUILT_LABELS_PALETTE_H_
#define ASBUILT_LABELS_PALETTE_H_

// The class-mapping dictionary of PAPER.md §3.3–3.4: reference colours of an
// ID map, each mapped to a label id. Rendered ID maps paint walls, doors and
// windows in annotation colours that drift with lighting (saturation,
// brightness, hue); calibration replaces the nominal colours by the measured
// centroid of each class, and conversion gives every pixel the class of its
// nearest reference colour (RGB Euclidean distance), or background beyond a
// threshold.
//
// palette.json:
//   {"version": 1, "method": "masks", "threshold": 96.3,
//    "colours": [{"class": "wall", "id": 1, "rgb": [231.4, 118.0, 102.9], "pixels": 812345,
//                 "rms_distance": 32.1},
//                ...]}
// `rgb` is 0..255 per channel (fractional for centroids); `id` is the label
// id (0 background, 1 wall, 2 door, 3 window); `class` is informative;
// `pixels` and `rms_distance` (optional) how many pixels the centroid was
// measured on and their RMS distance to it; `threshold` (optional) the
// suggested conversion threshold. Several colours may map to one id.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/formats/capture.h"  // FileReport

namespace asbuilt {

using Rgb = std::array<double, 3>;  // 0..255, red first.

struct PaletteColour {
  std::uint8_t id = 0;  // Label id this colour maps to.
  Rgb rgb = {0, 0, 0};
  std::int64_t pixels = 0;  // Pixels it was measured on; 0 = nominal.
  // RMS RGB distance of those pixels to `rgb` (the class's colour spread);
  // 0 = unknown.
  double rms_distance = 0.0;

  std::string ToString() const;  // "wall (1): rgb(231.4, 118.0, 102.9)"
};

struct Palette {
  std::vector<PaletteColour> colours;
  std::string method = "nominal";  // "nominal", "masks" or "kmeans".
  // Conversion threshold suggested by calibration (RGB distance): 3× the
  // largest class spread, so ≈ every pixel of a class stays within reach of
  // its centroid. Used by `labels convert` when no --threshold is given.
  std::optional<double> threshold;

  // The nominal annotation colours of asbuilt's renderer (render/renderer.h
  // kIdMapColors): background (0,0,0), wall (200,40,40), door (40,180,60),
  // window (40,80,200).
  static Palette Nominal();

  std::string ToString() const;  // "Palette(masks: background rgb(…), wall rgb(…), …)"
};

// Reads and validates a palette file; throws InputError naming the field
// (`palette.json: colours[1].rgb: expected 3 elements, got 2`).
Palette ReadPalette(const std::filesystem::path& path);
FileReport CheckPaletteFile(const std::filesystem::path& path);
// Writes atomically.
void WritePalette(const Palette& palette, const std::filesystem::path& path);
nlohmann::json PaletteToJson(const Palette& palette);

// Name of a label id for files and messages: "background", "wall", "door",
// "window", "ignore", else the number.
std::string LabelIdName(std::uint8_t id);

}  // namespace asbuilt

#endif  // ASBUILT_LABELS_PALETTE_H_
