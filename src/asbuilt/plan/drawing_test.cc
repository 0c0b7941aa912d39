#include "asbuilt/plan/drawing.h"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <utility>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/plan/dxf.h"
#include "asbuilt/plan/ifc.h"
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

// The room, its third corner (4.5, 3.6) moved `far_m` metres out along x:
// what a bad wall intersection makes of a plan.
Plan RoomWithAFarCorner(double far_m) {
  Plan plan = RoomWithDoorAndWindow();
  std::vector<Vec2> c = {{0, 0}, {4.5, 0}, {far_m, 3.6}, {0, 3.6}};
  for (int i = 0; i < 4; ++i) {
    plan.walls[i].start = c[i];
    plan.walls[i].end = c[(i + 1) % 4];
  }
  plan.openings.pop_back();  // The window was on the moved wall.
  plan.rooms[0].polygon = c;
  return plan;
}

// Size of an SVG drawing: on paper (its width/height in mm) and in the world
// (its viewBox, 1 unit = 1 m).
struct SvgSize {
  double width_mm = 0, height_mm = 0, width_m = 0, height_m = 0;
};
SvgSize ReadSvgSize(const std::string& svg) {
  SvgSize size;
  size_t at = svg.find("<svg ");
  EXPECT_NE(at, std::string::npos);
  size_t w = svg.find("width=\"", at), v = svg.find("viewBox=\"", at);
  EXPECT_EQ(std::sscanf(svg.c_str() + w, "width=\"%lfmm\" height=\"%lfmm\"", &size.width_mm, &size.height_mm), 2);
  EXPECT_EQ(std::sscanf(svg.c_str() + v, "viewBox=\"0 0 %lf %lf\"", &size.width_m, &size.height_m), 2);
  return size;
}

// Width and height of a PNG image from its IHDR chunk.
std::pair<int, int> PngSize(const std::string& png) {
  EXPECT_GE(png.size(), 24u);
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  auto be32 = [&](size_t at) {
    uint32_t v = 0;
    for (size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<uint8_t>(png[at + k]);
    return static_cast<int>(v);
  };
  return {be32(16), be32(20)};
}

// Page size of a one-page PDF from cairo, points.
std::pair<double, double> PdfPageSize(const std::string& pdf) {
  double w = 0, h = 0;
  size_t at = pdf.find("/MediaBox [");
  EXPECT_NE(at, std::string::npos);
  EXPECT_EQ(std::sscanf(pdf.c_str() + at, "/MediaBox [ 0 0 %lf %lf ]", &w, &h), 2);
  return {w, h};
}

TEST(DimensionText, IsMillimetresWithItsUncertaintyOfAtLeastOneMillimetre) {
  DrawingOptions o;
  EXPECT_EQ(DimensionText(4.5, 0.002, o), "4500 ±2");
  EXPECT_EQ(DimensionText(4.5, 0.0002, o), "4500 ±1");
  o.significant_sigma_m = 0.005;
  EXPECT_EQ(DimensionText(4.5, 0.002, o), "4500");
  o.significant_sigma_m = 0.0;
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
  for (const char* text : {">4500 ±4<", ">3600 ±12<", ">900<", ">1200<", ">16.20 ± 0.03 m²<", ">2 m<"}) {
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
  for (const char* name : {"plan.json", "plan.svg", "plan.dxf", "plan.pdf", "plan.png", "plan.ifc"}) {
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

TEST(PlanDrawings, AtTheRequestedScaleWhenThePlanFits) {
  EXPECT_EQ(PlanPageScale(RoomWithDoorAndWindow()), 50.0);
  EXPECT_EQ(PlanPngScale(RoomWithDoorAndWindow()), 50.0);
  std::string svg = PlanToSvg(RoomWithDoorAndWindow());
  EXPECT_NE(svg.find(">dimensions in mm, inner faces; 1:50<"), std::string::npos);
  SvgSize size = ReadSvgSize(svg);
  EXPECT_NEAR(size.width_m * 1000 / size.width_mm, 50.0, 0.1);
}

// A bad wall intersection puts a corner hundreds of metres (or a thousand
// kilometres) away: the drawings are still written, at a coarser scale that
// the title block states, within cairo's limits and the PNG cap.
TEST(PlanDrawings, PlanWithAFarCornerIsWrittenAtACoarserStatedScale) {
  for (double far_m : {500.0, 1e6}) {
    SCOPED_TRACE(far_m);
    const Plan plan = RoomWithAFarCorner(far_m);
    const DrawingOptions options;
    fs::path dir = fs::temp_directory_path() / "asbuilt_plan_far_corner";
    fs::remove_all(dir);
    fs::create_directories(dir);
    ASSERT_NO_THROW(WritePlanSvg(plan, dir / "plan.svg", options));
    ASSERT_NO_THROW(WritePlanPdf(plan, dir / "plan.pdf", options));
    ASSERT_NO_THROW(WritePlanPng(plan, dir / "plan.png", options));

    // SVG and PDF: one page scale, stated in the title block, that the page size matches.
    const double page_scale = PlanPageScale(plan, options);
    EXPECT_GT(page_scale, options.scale);
    std::string svg = ReadFile(dir / "plan.svg");
    EXPECT_NE(svg.find(fmt::format("; 1:{:.0f} (reduced from 1:50 to fit)<", page_scale)), std::string::npos);
    SvgSize page = ReadSvgSize(svg);
    EXPECT_GT(page.width_m, far_m);  // The whole plan is on the sheet.
    EXPECT_NEAR(page.width_m * 1000 / page.width_mm, page_scale, 1e-3 * page_scale);
    EXPECT_LE(std::max(page.width_mm, page.height_mm), options.max_page_side_mm);
    auto [pdf_w_pt, pdf_h_pt] = PdfPageSize(ReadFile(dir / "plan.pdf"));
    EXPECT_NEAR(pdf_w_pt, page.width_mm / 25.4 * 72, 0.5);
    EXPECT_NEAR(pdf_h_pt, page.height_mm / 25.4 * 72, 0.5);
    EXPECT_LE(std::max(pdf_w_pt, pdf_h_pt), 14400.0);

    // Text keeps its paper size: 0.13 m · 1.35 em at 1:50 is 3.51 mm.
    size_t font = svg.find("font-size=\"");
    ASSERT_NE(font, std::string::npos);
    double font_m = std::atof(svg.c_str() + font + 11);
    EXPECT_NEAR(font_m * 1000 / page_scale, 0.13 * 1.35 * 1000 / 50, 0.01);

    // PNG: its own scale, within the cap; its pixels are the sheet at that
    // scale and 6 px per paper mm (120 px/m at 1:50). The sheet is the SVG
    // page under the same limit in paper mm (8192 px / 6 px/mm).
    const double png_scale = PlanPngScale(plan, options);
    EXPECT_GE(png_scale, page_scale);
    auto [width_px, height_px] = PngSize(ReadFile(dir / "plan.png"));
    EXPECT_LE(std::max(width_px, height_px), options.max_png_side_px);
    EXPECT_GT(std::max(width_px, height_px), options.max_png_side_px / 10);  // Not needlessly small.
    const DrawingOptions png_page{.max_page_side_mm = options.max_png_side_px / 6.0};
    ASSERT_EQ(PlanPageScale(plan, png_page), png_scale);
    std::string png_sheet_svg = PlanToSvg(plan, png_page);
    EXPECT_NE(png_sheet_svg.find(fmt::format("; 1:{:.0f} (reduced from 1:50 to fit)<", png_scale)), std::string::npos);
    SvgSize png_sheet = ReadSvgSize(png_sheet_svg);
    const double px_per_m = 6000.0 / png_scale;
    EXPECT_NEAR(width_px, png_sheet.width_m * px_per_m, 1.0);
    EXPECT_NEAR(height_px, png_sheet.height_m * px_per_m, 1.0);
  }
}

// Two joined walls folding back on each other at a tiny angle: the outer
// faces' mitre would lie about 1.6 km away; it is bevelled instead.
TEST(PlanDrawings, SharpCornerIsBevelledNotMitredFarAway) {
  Plan plan;
  std::vector<Vec2> c = {{0, 0}, {4, 0}, {4, 3}, {8, 3}, {4, 3.001}, {0, 3}};
  for (size_t i = 0; i < c.size(); ++i) plan.walls.push_back({.start = c[i], .end = c[(i + 1) % c.size()]});
  plan.rooms.push_back({.polygon = c, .area_m2 = 12.002});
  EXPECT_EQ(PlanPageScale(plan), 50.0);
  EXPECT_EQ(PlanPngScale(plan), 50.0);
  SvgSize size = ReadSvgSize(PlanToSvg(plan));
  EXPECT_LT(size.width_m, 12.0);
  EXPECT_LT(size.height_m, 8.0);
}

// Nothing to draw (no walls), or walls of zero length and a room without
// area: the drawings show the scale bar and title block, at 1:50.
TEST(PlanDrawings, EmptyOrZeroSizedPlanDrawsTheTitleBlock) {
  Plan point;
  point.walls.push_back({.start = {3, 3}, .end = {3, 3}});
  point.rooms.push_back({.polygon = {{3, 3}, {3, 3}, {3, 3}}, .area_m2 = 0});
  for (const Plan& plan : {Plan{}, point}) {
    fs::path dir = fs::temp_directory_path() / "asbuilt_plan_empty";
    fs::remove_all(dir);
    ASSERT_NO_THROW(WritePlanFiles(plan, dir));
    std::string svg = ReadFile(dir / "plan.svg");
    EXPECT_NE(svg.find("; 1:50<"), std::string::npos);
    EXPECT_EQ(svg.find("nan"), std::string::npos);
    auto [width_px, height_px] = PngSize(ReadFile(dir / "plan.png"));
    EXPECT_GT(width_px, 100);
    EXPECT_GT(height_px, 10);
  }
}

TEST(PlanDrawings, NonFiniteCoordinateIsAnErrorNamingTheFileAndField) {
  Plan plan = RoomWithDoorAndWindow();
  plan.walls[1].end.x() = std::numeric_limits<double>::quiet_NaN();
  fs::path dir = fs::temp_directory_path() / "asbuilt_plan_nan";
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* name : {"plan.svg", "plan.pdf", "plan.png"}) {
    fs::path path = dir / name;
    try {
      if (path.extension() == ".svg") WritePlanSvg(plan, path);
      if (path.extension() == ".pdf") WritePlanPdf(plan, path);
      if (path.extension() == ".png") WritePlanPng(plan, path);
      ADD_FAILURE() << name << " written";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()),
                path.string() + ": cannot draw the plan: walls[1].end = (nan, 3.6) is not finite");
    }
    EXPECT_FALSE(fs::exists(path)) << name;
  }
  try {
    PlanToSvg(plan);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "plan: cannot draw the plan: walls[1].end = (nan, 3.6) is not finite");
  }
  plan = RoomWithDoorAndWindow();
  plan.openings[0].wall = 9;
  EXPECT_THROW(WritePlanPng(plan, dir / "plan.png"), Error);
  plan = RoomWithDoorAndWindow();
  plan.rooms[0].polygon[2].y() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(WritePlanPdf(plan, dir / "plan.pdf"), Error);
}

TEST(DrawingOptions, DefaultsAreValidAndBadValuesAreNamed) {
  EXPECT_NO_THROW(DrawingOptions{}.Check());
  try {
    DrawingOptions{.scale = 0}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "DrawingOptions.scale = 0, must be finite and > 0");
  }
  try {
    DrawingOptions{.max_page_side_mm = 6000}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "DrawingOptions.max_page_side_mm = 6000, must be in (0, 5080]");
  }
  try {
    DrawingOptions{.max_png_side_px = 40000}.Check();
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "DrawingOptions.max_png_side_px = 40000, must be in [16, 32767]");
  }
}

// An annotation larger than the page at every scale is an error naming the
// option; on a PNG it is drawn at a lower resolution instead.
TEST(PlanDrawings, AnnotationLargerThanTheLimitAtAnyScale) {
  const DrawingOptions tiny{.max_page_side_mm = 50, .max_png_side_px = 64};
  EXPECT_THROW(PlanToSvg(RoomWithDoorAndWindow(), tiny), Error);
  fs::path path = fs::temp_directory_path() / "asbuilt_plan_tiny.png";
  ASSERT_NO_THROW(WritePlanPng(RoomWithAFarCorner(500), path, tiny));
  auto [width_px, height_px] = PngSize(ReadFile(path));
  EXPECT_LE(std::max(width_px, height_px), 64);
}

TEST(PlanDrawings, AnUnreliablePlanSaysSoInEveryDrawing) {
  Plan plan = RoomWithDoorAndWindow();
  plan.verdict =
      PlanVerdictNote{.verdict = "unreliable", .confidence = 0.1, .reasons = {"walls found in 20 % of the turn"}};
  plan.walls[1].verdict = "unreliable";
  plan.walls[1].length_sigma_m.reset();
  const std::string svg = PlanToSvg(plan);
  EXPECT_NE(svg.find("UNRELIABLE - NOT A MEASUREMENT: walls found in 20 % of the turn"), std::string::npos);
  EXPECT_NE(svg.find("unreliable"), std::string::npos);  // Wall 1's length carries the word, not a ±.
  const std::string dxf = PlanToDxf(plan);
  EXPECT_NE(dxf.find("\nUNRELIABLE_NOT_A_MEASUREMENT\n"), std::string::npos);  // The layer, and text on it.
  EXPECT_EQ(dxf.find("CHECK_BEFORE_USE"), std::string::npos);
  const std::string ifc = PlanToIfc(plan);
  EXPECT_NE(ifc.find("'Verdict',"), std::string::npos);
  EXPECT_NE(ifc.find("IFCLABEL('unreliable')"), std::string::npos);
  // A plan with no verdict, or a good one, has no verdict layer or line.
  plan.verdict->verdict = "good";
  EXPECT_EQ(PlanToDxf(plan).find("NOT_A_MEASUREMENT"), std::string::npos);
  EXPECT_EQ(PlanToSvg(plan).find("NOT A MEASUREMENT"), std::string::npos);
}

}  // namespace
}  // namespace asbuilt
