#include "asbuilt/plan/drawing.h"

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

Plan RoomWithDoorAndWindow() {
  Plan plan;
  std::vector<Vec2> c = {{0, 0}, {4.5, 0}, {4.5, 3.6}, {0, 3.6}};
  for (int i = 0; i < 4; ++i) {
    plan.walls.push_back({.start = c[i], .end = c[(i + 1) % 4], .height = 2.7, .length_sigma_m = 0.004});
  }
  plan.walls[1].length_sigma_m = 0.012;
  plan.openings.push_back({.kind = OpeningKind::kDoor, .wall = 0, .start = {0.4, 0}, .end = {1.3, 0}, .width = 0.9});
  plan.openings.push_back(
      {.kind = OpeningKind::kWindow, .wall = 1, .start = {4.5, 0.9}, .end = {4.5, 2.1}, .width = 1.2});
  plan.rooms.push_back({.polygon = c, .area_m2 = 16.2, .area_sigma_m2 = 0.03});
  return plan;
}

TEST(DimensionText, IsMillimetresWithSignificantUncertainty) {
  DrawingOptions o;
  EXPECT_EQ(DimensionText(4.5, 0.002, o), "4500");
  EXPECT_EQ(DimensionText(3.6004, 0.012, o), "3600 ±12");
  EXPECT_EQ(DimensionText(0.9, std::nullopt, o), "900");
  o.show_uncertainty = false;
  EXPECT_EQ(DimensionText(3.6, 0.012, o), "3600");
}

TEST(PlanSvg, DrawsWallsDoorSwingWindowDimensionsAreaAndScaleBar) {
  std::string svg = PlanToSvg(RoomWithDoorAndWindow());
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<polygon"), std::string::npos);
  EXPECT_NE(svg.find(" A "), std::string::npos);  // Door swing arc.
  for (const char* text : {">4500<", ">3600 ±12<", ">900<", ">1200<", ">16.20 ± 0.03 m²<", ">2 m<"}) {
    EXPECT_NE(svg.find(text), std::string::npos) << text;
  }
  // Wall pieces: wall 0 is cut by the door (2 pieces), wall 1 by the window (2).
  size_t polygons = 0;
  for (size_t at = svg.find("<polygon"); at != std::string::npos; at = svg.find("<polygon", at + 1)) ++polygons;
  EXPECT_EQ(polygons, 6u + 1u + 4u);  // 6 wall pieces, the door leaf, 4 scale-bar blocks.
}

// An independent SVG reader (librsvg's rsvg-convert, Debian librsvg2-bin)
// parses the drawing and rasterises it to the drawing's size.
TEST(PlanSvg, RendersWithAnIndependentSvgReader) {
  if (std::system("command -v rsvg-convert > /dev/null 2>&1") != 0) GTEST_SKIP() << "rsvg-convert not installed";
  fs::path dir = fs::temp_directory_path() / "asbuilt_plan_svg";
  fs::create_directories(dir);
  WritePlanSvg(RoomWithDoorAndWindow(), dir / "plan.svg");
  fs::remove(dir / "plan.png");
  std::string cmd = "rsvg-convert " + (dir / "plan.svg").string() + " -o " + (dir / "plan.png").string() + " 2>&1";
  int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd;
  std::string png = ReadFile(dir / "plan.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(PlanFiles, WritesAllFiveAtomically) {
  fs::path dir = fs::temp_directory_path() / "asbuilt_plan_files";
  fs::remove_all(dir);
  WritePlanFiles(RoomWithDoorAndWindow(), dir);
  for (const char* name : {"plan.json", "plan.svg", "plan.dxf", "plan.pdf", "plan.png"}) {
    EXPECT_TRUE(fs::exists(dir / name)) << name;
    EXPECT_GT(fs::file_size(dir / name), 200u) << name;
  }
  std::string png = ReadFile(dir / "plan.png");
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(ReadFile(dir / "plan.pdf").substr(0, 5), "%PDF-");
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_FALSE(IsAtomicTempName(entry.path())) << entry.path();
  }
}

TEST(PlanFiles, FailsWithoutPartialOutputWhenTheFolderCannotBeMade) {
  fs::path file = fs::temp_directory_path() / "asbuilt_plan_not_a_folder";
  WriteFileAtomic(file, "x");
  EXPECT_THROW(WritePlanFiles(RoomWithDoorAndWindow(), file / "sub"), Error);
}

TEST(DrawingOptions, DefaultsAreValidAndBadValuesAreNamed) {
  EXPECT_NO_THROW(DrawingOptions{}.Check());
  try {
    DrawingOptions{.scale = 0}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "DrawingOptions.scale = 0, must be > 0");
  }
}

}  // namespace
}  // namespace asbuilt
