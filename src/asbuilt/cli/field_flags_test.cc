// FieldFlags (cli/field_flags.h) on a small list: WxH flags for two fields,
// flags given over a recipe, and the flags that give values back.

#include "asbuilt/cli/field_flags.h"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace asbuilt::cli {
namespace {

struct Box {
  int width_px = 64;
  int height_px = 48;
  double gain = 1.0;
  bool sharp = true;
  std::string mode = "fast";
};

const FieldList<Box>& BoxFields() {
  static const FieldList<Box> kList = {
      Bind(&Box::width_px, {.name = "width_px", .description = "W.", .minimum = 1.0, .maximum = 1000.0}),
      Bind(&Box::height_px, {.name = "height_px", .description = "H.", .minimum = 1.0, .maximum = 1000.0}),
      Bind(&Box::gain, {.name = "gain", .description = "G.", .exclusive_minimum = 0.0}),
      Bind(&Box::sharp, {.name = "sharp", .description = "S."}),
      BindChoice(&Box::mode, {.name = "mode", .description = "M.", .choices = {"fast", "slow"}}),
  };
  return kList;
}

// Parses `args` with the list's flags plus --size for width and height.
struct Parsed {
  CLI::App app{"test"};
  FieldFlags flags{app, BoxFields().Fields(), {{"gain", "--g"}}};
  explicit Parsed(std::vector<std::string> args) {
    flags.AddSize("width_px", "height_px", "--size", "box size");
    std::reverse(args.begin(), args.end());
    app.parse(args);
  }
};

TEST(FieldFlags, ASizeFlagSetsBothFields) {
  Parsed p({"--size", "320x200"});
  Box box;
  p.flags.Read(BoxFields(), box);
  EXPECT_EQ(box.width_px, 320);
  EXPECT_EQ(box.height_px, 200);
}

TEST(FieldFlags, ASizeFlagIsRefusedWithItsFieldsOwnFlagsOrWhenNotWxH) {
  Box box;
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"--size", "320x200", "--width-px", "10"}, {"--size", "320"}, {"--size", "0x5"}, {"--size", "3x4x5"}}) {
    Parsed p(args);
    EXPECT_THROW(p.flags.Read(BoxFields(), box), CLI::ValidationError) << args[1];
  }
}

TEST(FieldFlags, AValueOutOfBoundsFromASizeFlagNamesThatFlag) {
  Parsed p({"--size", "2000x10"});
  try {
    p.flags.Args();
    FAIL() << "2000 passed a maximum of 1000";
  } catch (const CLI::ValidationError& e) {
    EXPECT_NE(std::string(e.what()).find("--size (its --width-px): must be"), std::string::npos) << e.what();
  }
}

TEST(FieldFlags, ReadGivenKeepsWhatWasNotGiven) {
  Parsed p({"--g", "2.5", "--no-sharp"});
  Box recipe{.width_px = 7, .height_px = 9, .gain = 0.1, .sharp = true, .mode = "slow"};
  p.flags.ReadGiven(BoxFields(), recipe);
  EXPECT_EQ(recipe.width_px, 7);
  EXPECT_EQ(recipe.height_px, 9);
  EXPECT_EQ(recipe.mode, "slow");
  EXPECT_DOUBLE_EQ(recipe.gain, 2.5);
  EXPECT_FALSE(recipe.sharp);
}

TEST(FieldFlags, FieldFlagArgsGiveTheSameValuesBack) {
  const Box box{.width_px = 5, .height_px = 6, .gain = 0.25, .sharp = false, .mode = "slow"};
  const std::vector<std::string> args = FieldFlagArgs(BoxFields().Fields(), BoxFields().ToJson(box));
  EXPECT_EQ(args, (std::vector<std::string>{"--width-px", "5", "--height-px", "6", "--gain", "0.25", "--no-sharp",
                                            "--mode", "slow"}));
  Parsed p(args);
  Box back;
  p.flags.Read(BoxFields(), back);
  EXPECT_EQ(back.width_px, 5);
  EXPECT_EQ(back.height_px, 6);
  EXPECT_DOUBLE_EQ(back.gain, 0.25);
  EXPECT_FALSE(back.sharp);
  EXPECT_EQ(back.mode, "slow");
}

TEST(FieldFlags, AChoiceOutsideItsWordsIsRefusedByFlagAndByCheckValues) {
  Parsed p({"--mode", "medium"});
  EXPECT_THROW(p.flags.Args(), CLI::ValidationError);
  Box box;
  box.mode = "medium";
  try {
    BoxFields().CheckValues(box, "Box");
    FAIL() << "mode medium passed";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("Box.mode = \"medium\", must be one of fast, slow"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace asbuilt::cli
