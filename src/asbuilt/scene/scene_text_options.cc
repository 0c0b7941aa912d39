// SceneTextOptions' field list (scene_text.h): `asbuilt scene text` flags and
// the MCP tool scene_from_text.

#include "asbuilt/scene/scene_text.h"

namespace asbuilt {

const FieldList<SceneTextOptions>& SceneTextOptionFields() {
  using O = SceneTextOptions;
  static const FieldList<O> kList = {
      Bind(&O::furnish,
           {.name = "furnish", .description = "Add the room kind's usual furniture when the text names none."}),
      Bind(&O::add_door_if_none,
           {.name = "add_door_if_none",
            .description = "Give a room with no door mentioned a door (listed in the assumptions)."}),
      Bind(&O::rig_height_m, {.name = "rig_height_m",
                              .description = "Height of the default turn-in-place rig (capped below the ceiling).",
                              .exclusive_minimum = 0.0,
                              .maximum = 20.0}),
      Bind(&O::turn_step_deg, {.name = "turn_step_deg",
                               .description = "Yaw step of the default rig (30 → 12 views for a full turn).",
                               .exclusive_minimum = 0.0,
                               .maximum = 360.0}),
      Bind(&O::seed, {.name = "seed",
                      .description = "Seed for furniture placement (same text + seed → same scene).",
                      .minimum = 0.0,
                      .maximum = 4294967295.0}),
  };
  return kList;
}

}  // namespace asbuilt
