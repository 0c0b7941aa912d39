#include "asbuilt/labels/palette.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path PaletteTestDir() {
  fs::path dir = fs::temp_directory_path() /
                 ("asbuilt_palette_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  fs::remove_all(dir);
  return dir;
}

TEST(Palette, NominalPrintsItself) {
  EXPECT_EQ(Palette::Nominal().ToString(),
            "Palette(nominal: background rgb(0.0, 0.0, 0.0), wall rgb(200.0, 40.0, 40.0), "
            "door rgb(40.0, 180.0, 60.0), window rgb(40.0, 80.0, 200.0))");
  EXPECT_EQ(Palette::Nominal().colours[1].ToString(), "wall (1): rgb(200.0, 40.0, 40.0)");
}

TEST(Palette, RoundTrips) {
  fs::path dir = PaletteTestDir();
  Palette p = Palette::Nominal();
  p.method = "masks";
  p.colours[1].rgb = {201.25, 55.5, 50.125};
  p.colours[1].pixels = 1234;
  WritePalette(p, dir / "palette.json");
  Palette r = ReadPalette(dir / "palette.json");
  EXPECT_EQ(PaletteToJson(r), PaletteToJson(p));
  EXPECT_EQ(r.method, "masks");
  EXPECT_DOUBLE_EQ(r.colours[1].rgb[2], 50.125);
  EXPECT_EQ(r.colours[1].pixels, 1234);
}

TEST(Palette, ErrorsNameTheField) {
  fs::path dir = PaletteTestDir();
  WriteFileAtomic(dir / "palette.json", R"({"version": 1, "colours": [
      {"class": "wall", "id": 1, "rgb": [220, 60]},
      {"class": "door", "id": 7, "rgb": [0, 300, 0]}]})");
  FileReport report = CheckPaletteFile(dir / "palette.json");
  ASSERT_EQ(report.errors.size(), 3u);
  EXPECT_EQ(report.errors[0].ToString(),
            (dir / "palette.json").string() + ": colours[0].rgb: expected 3 elements, got 2");
  EXPECT_EQ(report.errors[1].field_path, "colours[1].id");
  EXPECT_EQ(report.errors[1].message, "must be a label id 0..3 (background, wall, door, window), got 7");
  EXPECT_EQ(report.errors[2].message, "channel 1 = 300 is outside 0..255");
  EXPECT_THROW(ReadPalette(dir / "palette.json"), InputError);
}

TEST(Palette, EmptyColourListIsAnError) {
  fs::path dir = PaletteTestDir();
  WriteFileAtomic(dir / "palette.json", R"({"version": 1, "colours": []})");
  FileReport report = CheckPaletteFile(dir / "palette.json");
  ASSERT_EQ(report.errors.size(), 1u);
  EXPECT_EQ(report.errors[0].field_path, "colours");
}

}  // namespace
}  // namespace asbuilt
