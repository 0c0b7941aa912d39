// RandomSceneOptions' field list (procedural.h): `asbuilt scene random` flags
// and the MCP tool random_scene.

#include "asbuilt/scene/procedural.h"

namespace asbuilt {

Field RandomSceneSeedField() {
  return {.name = "seed",
          .kind = FieldKind::kInteger,
          .description = "Seed of the (first) scene; same options + seed → same scene.",
          .minimum = 0.0,
          .maximum = 4294967295.0,
          .default_value = 0};
}

const FieldList<RandomSceneOptions>& RandomSceneOptionFields() {
  using O = RandomSceneOptions;
  auto probability = [](double O::*member, std::string_view name, std::string_view description) {
    return Bind(member, {.name = std::string(name), .description = description, .minimum = 0.0, .maximum = 1.0});
  };
  static const FieldList<O> kList = {
      Bind(&O::min_side_m, {.name = "min_side_m",
                            .description = "Smallest side of the room's bounding box.",
                            .minimum = 1.5,
                            .maximum = 100.0}),
      Bind(&O::max_side_m, {.name = "max_side_m",
                            .description = "Largest side of the room's bounding box (>= min_side_m).",
                            .minimum = 1.5,
                            .maximum = 100.0}),
      Bind(&O::min_height_m,
           {.name = "min_height_m", .description = "Lowest ceiling.", .minimum = 2.2, .maximum = 20.0}),
      Bind(&O::max_height_m, {.name = "max_height_m",
                              .description = "Highest ceiling (>= min_height_m).",
                              .minimum = 2.2,
                              .maximum = 20.0}),
      probability(&O::l_shape_probability, "l_shape_probability", "Share of L-shaped rooms."),
      probability(&O::rotated_probability, "rotated_probability", "Share of rooms turned by a random angle."),
      Bind(&O::min_openings, {.name = "min_openings",
                              .description = "Fewest doors + windows per room (the first is always a door).",
                              .minimum = 1.0,
                              .maximum = 12.0}),
      Bind(&O::max_openings, {.name = "max_openings",
                              .description = "Most doors + windows per room (>= min_openings).",
                              .minimum = 1.0,
                              .maximum = 12.0}),
      probability(&O::same_wall_probability, "same_wall_probability",
                  "Chance an opening joins a wall that already has one."),
      probability(&O::corner_door_probability, "corner_door_probability", "Chance a door sits tight in a corner."),
      Bind(&O::min_furniture, {.name = "min_furniture",
                               .description = "Fewest furniture pieces tried per room (some may not fit).",
                               .minimum = 0.0,
                               .maximum = 64.0}),
      Bind(&O::max_furniture, {.name = "max_furniture",
                               .description = "Most furniture pieces tried per room (>= min_furniture).",
                               .minimum = 0.0,
                               .maximum = 64.0}),
      Bind(&O::turn_step_deg, {.name = "turn_step_deg",
                               .description = "Rig yaw step; 360 / step views.",
                               .exclusive_minimum = 0.0,
                               .maximum = 360.0}),
      BindEnum(&O::rig_spot,
               {.name = "rig_spot",
                .description = "Where the rig stands: random (anywhere 0.8 m clear of the walls, for training "
                               "views) or survey (where a surveyor would: the spot that sees every wall, farthest "
                               "from them)."},
               {{RigSpotName(RigSpot::kRandom), RigSpot::kRandom}, {RigSpotName(RigSpot::kSurvey), RigSpot::kSurvey}}),
  };
  return kList;
}

}  // namespace asbuilt
