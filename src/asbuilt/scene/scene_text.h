#ifndef ASBUILT_SCENE_SCENE_TEXT_H_
#define ASBUILT_SCENE_SCENE_TEXT_H_

// The built-in text → scene parser (no network). Understands room sizes
// ("6 by 8 m", "6m x 8m", "20 square metres"), heights ("3 m high",
// "ceiling 2.7 m"), room kinds with default sizes and furniture
// ("classroom", "bedroom", "living room", …), L-shaped and rotated rooms,
// doors and windows with counts (words or digits), sizes, walls by compass
// direction (north = +Y, east = +X) and simple positions ("in the corner",
// "centred", "near the west end", "1 m from the north end"), materials
// ("white walls", "wooden floor"), furniture, lights and the rig. The
// grammar is documented in docs/scene.md.
//
// Words it cannot use are returned in `unused_words` (and logged as a
// warning), never silently dropped; defaults it chose are listed in
// `assumptions`.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "asbuilt/scene/scene.h"
#include "asbuilt/util/fields.h"

namespace asbuilt {

struct SceneTextOptions {
  double rig_height_m = 1.5;     // Height of the default turn-in-place rig (capped below the ceiling).
  double turn_step_deg = 30.0;   // Yaw step of the default rig; 12 views for a full turn.
  bool furnish = true;           // Add the room kind's usual furniture when the text names none.
  bool add_door_if_none = true;  // A room with no door mentioned gets one (listed in assumptions).
  std::uint64_t seed = 0;        // Furniture placement; same text + seed → same scene.

  void Check() const;
};
// Its field list: the flags of `asbuilt scene text` and the arguments of the
// MCP tool scene_from_text (scene_text_options.cc).
const FieldList<SceneTextOptions>& SceneTextOptionFields();

struct SceneTextResult {
  Scene scene;                            // Valid (CheckScene passed).
  std::vector<std::string> unused_words;  // Words not understood, in text order.
  std::vector<std::string> assumptions;   // Defaults chosen ("no size given: bedroom default 3.50 × 4.00 m").

  // "classroom: 6.00 × 8.00 m, 3 openings, 12 views; 1 word not understood: \"giraffe\"".
  std::string BriefReport() const;
};

// Parses a room description. Throws InputError (file "text") when the text
// asks for something impossible (openings that do not fit their wall, a
// cut-out larger than the room, a window above the ceiling) or contains
// nothing the parser understands; the message says which part. A text that
// names no room kind or size gets a generic 4 × 5 m room (an assumption).
SceneTextResult SceneFromText(std::string_view text, const SceneTextOptions& options = {});

}  // namespace asbuilt

#endif  // ASBUILT_SCENE_SCENE_TEXT_H_
