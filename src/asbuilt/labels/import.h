#ifndef ASBUILT_LABELS_IMPORT_H_
#define ASBUILT_LABELS_IMPORT_H_

// Real annotations in: converts the annotation formats people already have
// into asbuilt label maps (0 background, 1 wall, 2 door, 3 window, 255
// ignore; single-channel 8-bit PNG).
//
//   ade20k   SceneParsing-150 masks (8-bit, raw class index): 1 wall → wall,
//            9 windowpane → window, 15 "door;double;door" (doors and double
//            doors) and 59 "screen;door;screen" (screen doors) → door;
//            0 (unlabelled, not evaluated by ADE) → ignore; others → background.
//   nyuv2    NYUv2 40-class masks (Gupta et al.): 1 wall, 8 door, 9 window;
//            0 (void) → ignore; others → background.
//   labelme  LabelMe JSON polygons (polygon, rectangle, circle), drawn in file
//            order (later shapes on top) on an imageWidth × imageHeight map;
//            label names (case-insensitive): wall(s); door(s), double door,
//            doorway, screen door; window(s), windowpane, window pane;
//            ignore/__ignore__/void → 255; anything else → background.
//   palette  colour-palette mask PNGs (each class painted in one colour):
//            the nearest colour of a palette file within a threshold.

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/labels/palette.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

enum class AnnotationFormat { kAde20k, kNyu40, kLabelMe, kPalette };
const char* AnnotationFormatName(AnnotationFormat format);  // "ade20k", "nyuv2", "labelme", "palette"
std::optional<AnnotationFormat> ParseAnnotationFormat(std::string_view name);

struct ImportOptions {
  AnnotationFormat format = AnnotationFormat::kAde20k;
  // ADE20K / NYUv2 "unlabelled" (0): ignore (255) so training skips it, or
  // background (0) when false.
  bool unlabeled_to_ignore = true;
  // palette: the colours of the masks (required, non-empty), and the RGB
  // distance within which a pixel takes a colour's class (JPEG'd or
  // anti-aliased masks need some slack); beyond → background.
  Palette palette;
  double palette_threshold = 30.0;
  // labelme: extra or overriding label names (lowercase) → label id.
  std::map<std::string, std::uint8_t> labelme_names;
  int num_threads = 0;  // 0 = all cores.

  void Check() const;
};

// The id mappings as lookup tables (raw id → asbuilt id).
std::array<std::uint8_t, 256> Ade20kMapping(bool unlabeled_to_ignore);
std::array<std::uint8_t, 256> Nyu40Mapping(bool unlabeled_to_ignore);
// The label id of a LabelMe label name (default table + options.labelme_names).
std::uint8_t LabelMeNameToId(std::string_view name, const ImportOptions& options);

// One annotation file → CV_8UC1 label map. Throws InputError naming the file
// (and the JSON field for LabelMe): undecodable, wrong channel count, a raw
// id outside the format's range (e.g. 57 in a NYUv2-40 mask), a bad polygon.
cv::Mat ImportAnnotation(const std::filesystem::path& input, const ImportOptions& options);
// LabelMe from parsed text (for tests and the MCP server); `file` names it in errors.
cv::Mat ImportLabelMeJson(std::string_view json_text, const std::string& file, const ImportOptions& options);

struct ImportSummary {
  AnnotationFormat format = AnnotationFormat::kAde20k;
  int imported = 0;
  std::vector<Problem> failed;  // One per input that could not be imported.
  // Pixels written per id: [0..3] classes, [4] ignore (255).
  std::array<std::int64_t, 5> class_pixels{};
  double seconds = 0.0;

  // "imported 4 ade20k annotations in 0.05 s: background 61.2 %, wall 19.4 %, …"
  std::string BriefReport() const;
};

// Imports each input into output_dir/<stem>.png, in parallel, atomically. A
// bad input is recorded in `failed` and the others go on.
ImportSummary ImportAnnotations(const ImportOptions& options, const std::vector<std::filesystem::path>& inputs,
                                const std::filesystem::path& output_dir, const ProgressCallback& progress = {});

// The inputs of a format inside `dir` (*.json for labelme, images otherwise),
// sorted. Throws InputError if `dir` is not a folder.
std::vector<std::filesystem::path> ListAnnotationFiles(const std::filesystem::path& dir, AnnotationFormat format);

}  // namespace asbuilt

#endif  // ASBUILT_LABELS_IMPORT_H_
