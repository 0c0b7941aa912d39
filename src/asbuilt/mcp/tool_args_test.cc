#include "asbuilt/mcp/tool_args.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace asbuilt::mcp {
namespace {

using ::testing::HasSubstr;

const std::vector<ToolField>& Fields() {
  static const std::vector<ToolField> kFields = {
      {.name = "width_m", .type = ArgType::kNumber, .description = "Width.", .required = true,
       .exclusive_minimum = 0.0, .maximum = 100.0},
      {.name = "wall", .type = ArgType::kInteger, .description = "Wall.", .minimum = 0.0},
      {.name = "side", .type = ArgType::kEnum, .description = "Side.",
       .choices = {"north", "south"}},
      {.name = "polygon", .type = ArgType::kPolygon, .description = "Corners.", .min_items = 3,
       .max_items = 4},
      {.name = "colour", .type = ArgType::kColor, .description = "Colour."},
      {.name = "height_m", .type = ArgType::kNumber, .description = "Height.",
       .default_value = 2.7},
      {.name = "name", .type = ArgType::kString, .description = "Name.", .max_length = 5},
  };
  return kFields;
}

std::string ErrorOf(const nlohmann::json& args) {
  try {
    ParseToolArgs(Fields(), args);
  } catch (const ToolArgsError& e) {
    return e.what();
  }
  return "";
}

TEST(ToolInputSchema, ListsPropertiesBoundsAndRequired) {
  nlohmann::json s = ToolInputSchema(Fields());
  EXPECT_EQ(s["type"], "object");
  EXPECT_EQ(s["additionalProperties"], false);
  EXPECT_EQ(s["required"], nlohmann::json::array({"width_m"}));
  EXPECT_EQ(s["properties"]["width_m"]["type"], "number");
  EXPECT_EQ(s["properties"]["width_m"]["exclusiveMinimum"], 0.0);
  EXPECT_EQ(s["properties"]["width_m"]["maximum"], 100.0);
  EXPECT_EQ(s["properties"]["wall"]["type"], "integer");
  EXPECT_EQ(s["properties"]["side"]["enum"], nlohmann::json::array({"north", "south"}));
  EXPECT_EQ(s["properties"]["polygon"]["minItems"], 3);
  EXPECT_EQ(s["properties"]["polygon"]["items"]["minItems"], 2);
  EXPECT_EQ(s["properties"]["colour"]["items"]["maximum"], 1.0);
  EXPECT_EQ(s["properties"]["height_m"]["default"], 2.7);
  EXPECT_EQ(s["properties"]["name"]["maxLength"], 5);
}

TEST(ParseToolArgs, ReadsValuesAndDefaults) {
  ToolArgs a = ParseToolArgs(Fields(), {{"width_m", 6}, {"wall", 2}, {"side", "north"},
                                        {"polygon", {{0, 0}, {1, 0}, {1, 1}}},
                                        {"colour", {0.1, 0.2, 0.3}}});
  EXPECT_EQ(a.Number("width_m"), 6.0);
  EXPECT_EQ(a.Integer("wall"), 2);
  EXPECT_EQ(a.String("side"), "north");
  EXPECT_EQ(a.Points("polygon").size(), 3u);
  EXPECT_EQ(a.Numbers("colour")[2], 0.3);
  EXPECT_EQ(a.Number("height_m"), 2.7);  // Default.
  EXPECT_FALSE(a.Has("name"));
  EXPECT_FALSE(a.OptString("name"));
  // A whole float is accepted as an integer.
  EXPECT_EQ(ParseToolArgs(Fields(), {{"width_m", 1}, {"wall", 3.0}}).Integer("wall"), 3);
}

TEST(ParseToolArgs, NamesEveryBadArgumentAndWhatIsAllowed) {
  std::string e = ErrorOf({{"width_m", -2}, {"wall", 1.5}, {"side", "up"}, {"colour", {2, 0, 0}},
                           {"name", "toolong"}, {"widht_m", 3}});
  EXPECT_THAT(e, HasSubstr("arguments.width_m: must be > 0 and <= 100, got -2"));
  EXPECT_THAT(e, HasSubstr("arguments.wall: must be a whole number"));
  EXPECT_THAT(e, HasSubstr("arguments.side: must be one of \"north\", \"south\", got \"up\""));
  EXPECT_THAT(e, HasSubstr("arguments.colour[0]: must be >= 0 and <= 1, got 2"));
  EXPECT_THAT(e, HasSubstr("arguments.name: must be at most 5 characters"));
  EXPECT_THAT(e, HasSubstr("arguments.widht_m: unknown argument; allowed: width_m, wall"));
}

TEST(ParseToolArgs, RequiredAndWrongTypes) {
  EXPECT_THAT(ErrorOf(nlohmann::json::object()), HasSubstr("arguments.width_m: required"));
  EXPECT_THAT(ErrorOf({{"width_m", "6"}}), HasSubstr("arguments.width_m: must be a finite number, got \"6\""));
  EXPECT_THAT(ErrorOf({{"width_m", 1}, {"polygon", {{0, 0}, {1, 0}}}}),
              HasSubstr("arguments.polygon: must have 3 to 4 points, got 2"));
  EXPECT_THAT(ErrorOf({{"width_m", 1}, {"polygon", {{0, 0}, {1, 0}, {1, "a"}}}}),
              HasSubstr("arguments.polygon[2]: must be [x, y]"));
  EXPECT_THAT(ErrorOf(nlohmann::json::array()), HasSubstr("arguments: must be an object"));
}

TEST(ToolFieldsMarkdown, OneRowPerField) {
  std::string md = ToolFieldsMarkdown(Fields());
  EXPECT_THAT(md, HasSubstr("| `width_m` | number > 0 and <= 100 | required | Width. |"));
  EXPECT_THAT(md, HasSubstr("| `height_m` | number | `2.7` | Height. |"));
}

}  // namespace
}  // namespace asbuilt::mcp
