#include "asbuilt/util/fields.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace asbuilt {
namespace {

using ::testing::HasSubstr;

const std::vector<Field>& Fields() {
  static const std::vector<Field> kFields = {
      {.name = "width_m",
       .kind = FieldKind::kNumber,
       .description = "Width.",
       .required = true,
       .exclusive_minimum = 0.0,
       .maximum = 100.0},
      {.name = "wall", .kind = FieldKind::kInteger, .description = "Wall.", .minimum = 0.0},
      {.name = "side", .kind = FieldKind::kEnum, .description = "Side.", .choices = {"north", "south"}},
      {.name = "polygon", .kind = FieldKind::kPolygon, .description = "Corners.", .min_items = 3, .max_items = 4},
      {.name = "colour", .kind = FieldKind::kColor, .description = "Colour."},
      {.name = "height_m", .kind = FieldKind::kNumber, .description = "Height.", .default_value = 2.7},
      {.name = "name", .kind = FieldKind::kString, .description = "Name.", .max_length = 5},
  };
  return kFields;
}

std::string ErrorOf(const nlohmann::json& args) {
  try {
    ParseFieldArgs(Fields(), args);
  } catch (const FieldArgsError& e) {
    return e.what();
  }
  return "";
}

TEST(FieldsSchema, ListsPropertiesBoundsAndRequired) {
  nlohmann::json s = FieldsSchema(Fields());
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

TEST(ParseFieldArgs, ReadsValuesAndDefaults) {
  FieldArgs a = ParseFieldArgs(Fields(), {{"width_m", 6},
                                          {"wall", 2},
                                          {"side", "north"},
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
  EXPECT_EQ(ParseFieldArgs(Fields(), {{"width_m", 1}, {"wall", 3.0}}).Integer("wall"), 3);
}

TEST(ParseFieldArgs, NamesEveryBadArgumentAndWhatIsAllowed) {
  std::string e = ErrorOf(
      {{"width_m", -2}, {"wall", 1.5}, {"side", "up"}, {"colour", {2, 0, 0}}, {"name", "toolong"}, {"widht_m", 3}});
  EXPECT_THAT(e, HasSubstr("arguments.width_m: must be > 0 and <= 100, got -2"));
  EXPECT_THAT(e, HasSubstr("arguments.wall: must be a whole number"));
  EXPECT_THAT(e, HasSubstr("arguments.side: must be one of \"north\", \"south\", got \"up\""));
  EXPECT_THAT(e, HasSubstr("arguments.colour[0]: must be >= 0 and <= 1, got 2"));
  EXPECT_THAT(e, HasSubstr("arguments.name: must be at most 5 characters"));
  EXPECT_THAT(e, HasSubstr("arguments.widht_m: unknown argument; allowed: width_m, wall"));
}

TEST(ParseFieldArgs, RequiredAndWrongTypes) {
  EXPECT_THAT(ErrorOf(nlohmann::json::object()), HasSubstr("arguments.width_m: required"));
  EXPECT_THAT(ErrorOf({{"width_m", "6"}}), HasSubstr("arguments.width_m: must be a finite number, got \"6\""));
  EXPECT_THAT(ErrorOf({{"width_m", 1}, {"polygon", {{0, 0}, {1, 0}}}}),
              HasSubstr("arguments.polygon: must have 3 to 4 points, got 2"));
  EXPECT_THAT(ErrorOf({{"width_m", 1}, {"polygon", {{0, 0}, {1, 0}, {1, "a"}}}}),
              HasSubstr("arguments.polygon[2]: must be [x, y]"));
  EXPECT_THAT(ErrorOf(nlohmann::json::array()), HasSubstr("arguments: must be an object"));
}

TEST(FieldsMarkdown, OneRowPerField) {
  std::string md = FieldsMarkdown(Fields());
  EXPECT_THAT(md, HasSubstr("| `width_m` | number > 0 and <= 100 | required | Width. |"));
  EXPECT_THAT(md, HasSubstr("| `height_m` | number | `2.7` | Height. |"));
}

}  // namespace

// ------------------------------------------------------------- FieldList

namespace {

enum class Shade { kLight, kDark };

struct InnerOptions {
  int block_px = 5;
  bool fill = false;
};

struct OuterOptions {
  double epsilon_m = 0.05;
  std::optional<int> snap_px;
  Shade shade = Shade::kDark;
  std::string name = "room";
  InnerOptions inner = {.block_px = 7};
};

const FieldList<InnerOptions>& InnerFields() {
  static const FieldList<InnerOptions> kList = {
      Bind(&InnerOptions::block_px, {.name = "block_px", .description = "Block.", .minimum = 1.0}),
      Bind(&InnerOptions::fill, {.name = "fill", .description = "Fill."}),
  };
  return kList;
}

const FieldList<OuterOptions>& OuterFields() {
  static const FieldList<OuterOptions> kList = [] {
    FieldList<OuterOptions> list = {
        Bind(&OuterOptions::epsilon_m, {.name = "epsilon_m", .description = "Tolerance.", .exclusive_minimum = 0.0}),
        Bind(&OuterOptions::snap_px, {.name = "snap_px", .description = "Snap.", .minimum = 0.0}),
        BindEnum(&OuterOptions::shade, {.name = "shade", .description = "Shade."},
                 {{"light", Shade::kLight}, {"dark", Shade::kDark}}),
        Bind(&OuterOptions::name, {.name = "name", .description = "Name."}),
    };
    list.Nest("inner", &OuterOptions::inner, InnerFields());
    return list;
  }();
  return kList;
}

}  // namespace

TEST(FieldList, KindsAndDefaultsComeFromTheStruct) {
  std::vector<Field> fields = OuterFields().Fields();
  ASSERT_EQ(fields.size(), 6u);
  EXPECT_EQ(fields[0].kind, FieldKind::kNumber);
  EXPECT_EQ(fields[0].default_value, 0.05);
  EXPECT_EQ(fields[1].kind, FieldKind::kInteger);
  EXPECT_TRUE(fields[1].default_value.is_null());  // Unset optional: no default.
  EXPECT_EQ(fields[2].kind, FieldKind::kEnum);
  EXPECT_EQ(fields[2].choices, (std::vector<std::string_view>{"light", "dark"}));
  EXPECT_EQ(fields[2].default_value, "dark");
  EXPECT_EQ(fields[3].kind, FieldKind::kString);
  // Nested: prefixed names, defaults of the outer struct's member.
  EXPECT_EQ(fields[4].name, "inner.block_px");
  EXPECT_EQ(fields[4].default_value, 7);
  EXPECT_EQ(fields[5].name, "inner.fill");
  EXPECT_EQ(fields[5].kind, FieldKind::kBool);
}

TEST(FieldList, ReadsValuesIntoTheStructIncludingNestedOnes) {
  const FieldList<OuterOptions>& list = OuterFields();
  FieldArgs args =
      ParseFieldArgs(list.Fields(), {{"epsilon_m", 0.02}, {"snap_px", 4}, {"shade", "light"}, {"inner.block_px", 9}});
  OuterOptions o = list.FromArgs(args);
  EXPECT_EQ(o.epsilon_m, 0.02);
  EXPECT_EQ(o.snap_px, 4);
  EXPECT_EQ(o.shade, Shade::kLight);
  EXPECT_EQ(o.name, "room");
  EXPECT_EQ(o.inner.block_px, 9);
  EXPECT_FALSE(o.inner.fill);
  EXPECT_EQ(list.ToJson(o)["inner.block_px"], 9);

  OuterOptions unset = list.FromArgs(ParseFieldArgs(list.Fields(), nullptr));
  EXPECT_FALSE(unset.snap_px.has_value());
  EXPECT_EQ(unset.inner.block_px, 7);
  EXPECT_FALSE(list.ToJson(unset).contains("snap_px"));
}

TEST(FieldList, BadNestedValueNamesTheNestedField) {
  try {
    ParseFieldArgs(OuterFields().Fields(), {{"inner.block_px", 0}, {"epsilon_m", -1}});
    FAIL() << "no error";
  } catch (const FieldArgsError& e) {
    EXPECT_THAT(e.what(), HasSubstr("arguments.inner.block_px: must be an integer >= 1, got 0"));
    EXPECT_THAT(e.what(), HasSubstr("arguments.epsilon_m: must be > 0, got -1"));
  }
}

}  // namespace asbuilt
