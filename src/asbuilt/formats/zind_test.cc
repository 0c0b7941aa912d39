#include "asbuilt/formats/zind.h"

#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

const fs::path kSampleTour = fs::path(ASBUILT_SHARED_DATA_DIR) / "zind_sample_tour";

#define SKIP_WITHOUT_SAMPLE_TOUR() \
  if (!fs::exists(kSampleTour / "zind_data.json")) GTEST_SKIP() << "shared data not present: " << kSampleTour

TEST(ZindTour, ReadsTheSampleTour) {
  SKIP_WITHOUT_SAMPLE_TOUR();
  const ZindTour tour = ReadZindTour(kSampleTour);
  EXPECT_EQ(tour.panoramas.size(), 32u);
  // Issue 21: 13 primary panoramas taken inside their room.
  const std::vector<const ZindPanorama*> bench = tour.BenchmarkPanoramas();
  ASSERT_EQ(bench.size(), 13u);
  for (const ZindPanorama* p : bench) {
    EXPECT_TRUE(p->is_primary && p->is_inside) << p->Name();
    EXPECT_TRUE(fs::is_regular_file(p->image)) << p->image;
  }
  EXPECT_EQ(tour.ToString(),
            fmt::format("ZInD tour {}: 32 panoramas, 19 primary, 13 primary inside", kSampleTour.string()));
  // Natural order: pano_2 before pano_4 in partial_room_09.
  EXPECT_EQ(tour.Find("floor_01/complete_room_06/partial_room_09/pano_2"), tour.Find("pano_2"));
  EXPECT_EQ(tour.Find("panos/floor_01_partial_room_01_pano_15.jpg")->pano_id, "pano_15");
  EXPECT_EQ(tour.Find("pano_99"), nullptr);
}

TEST(ZindTour, GivesTheBonusRoomInMetres) {
  SKIP_WITHOUT_SAMPLE_TOUR();
  const ZindTour tour = ReadZindTour(kSampleTour);
  const ZindPanorama& p = *tour.Find("pano_15");
  // The sample tour's README: scale 0.4042260417 × 3.5500877 m per unit.
  EXPECT_TRUE(p.metric);
  EXPECT_NEAR(p.metres_per_unit, 0.4042260417272217 * 3.550087732889448, 1e-12);
  EXPECT_NEAR(p.camera_height_m, 1.43503, 1e-5);
  EXPECT_NEAR(p.ceiling_height_m, 1.631486020994743 * p.metres_per_unit, 1e-9);
  EXPECT_EQ(p.label, "bonus room");
  ASSERT_EQ(p.layout_raw.vertices_m.size(), 4u);
  // ZInD (1.4821, −1.0930) mirrored and scaled.
  EXPECT_NEAR(p.layout_raw.vertices_m[0].x(), 1.48215792618098 * p.metres_per_unit, 1e-9);
  EXPECT_NEAR(p.layout_raw.vertices_m[0].y(), 1.0929678418538107 * p.metres_per_unit, 1e-9);
  EXPECT_NEAR(std::abs(PolygonArea(p.layout_raw.vertices_m)), 15.60, 0.01);
  ASSERT_EQ(p.layout_raw.openings.size(), 3u);
  const ZindOpening& glass = p.layout_raw.openings[0];  // The sliding glass door.
  EXPECT_EQ(glass.kind, ZindOpeningKind::kDoor);
  EXPECT_EQ(glass.wall, 1);
  EXPECT_LT(glass.offset_m, 0.001);
  EXPECT_NEAR(glass.Width(), 1.70, 0.01);
  EXPECT_NEAR(glass.bottom_m, 0.01, 0.01);
  EXPECT_NEAR(glass.top_m, 1.91, 0.01);
  EXPECT_EQ(glass.ToString(), "door 1.70 m wide, 0.01–1.91 m on wall 1");
  EXPECT_EQ(p.layout_raw.openings[1].wall, 3);
  EXPECT_EQ(p.layout_raw.openings[2].wall, 0);
  EXPECT_EQ(p.ToString(),
            "pano_15 (bonus room, primary, inside): camera 1.435 m, ceiling 2.34 m, 4 walls, 3 doors, 0 windows, "
            "0 passages");
}

TEST(ZindTour, PlacesEveryOpeningOfTheSampleTourOnAWall) {
  SKIP_WITHOUT_SAMPLE_TOUR();
  const ZindTour tour = ReadZindTour(kSampleTour);
  int openings = 0;
  for (const ZindPanorama& p : tour.panoramas) {
    for (const ZindOpening& o : p.layout_raw.openings) {
      EXPECT_GE(o.wall, 0) << p.Name() << " " << o.ToString();
      EXPECT_LT(o.bottom_m, o.top_m);
      EXPECT_LE(o.top_m, p.ceiling_height_m + 0.1) << p.Name() << " " << o.ToString();
      ++openings;
    }
  }
  EXPECT_GT(openings, 50);
}

// Two panoramas of one partial room were annotated separately; taken to the
// floor's frame, their raw layouts must be the same room.
TEST(ZindTour, FloorFromPanoBringsTwoPanoramasOfARoomTogether) {
  SKIP_WITHOUT_SAMPLE_TOUR();
  const ZindTour tour = ReadZindTour(kSampleTour);
  const ZindPanorama& a = *tour.Find("pano_15");
  const ZindPanorama& b = *tour.Find("pano_14");
  ASSERT_EQ(a.partial_room_id, b.partial_room_id);
  ASSERT_TRUE(a.layout_complete && b.layout_complete);
  // Each corner of a's complete layout has a corner of b's within 5 cm.
  for (const Vec2& va : a.layout_complete->vertices_m) {
    const Vec2 fa = a.floor_from_pano * va;
    double nearest = 1e9;
    for (const Vec2& vb : b.layout_complete->vertices_m)
      nearest = std::min(nearest, (b.floor_from_pano * vb - fa).norm());
    EXPECT_LT(nearest, 0.05) << fa.transpose();
  }
  // And the two cameras are apart, as they were in the house.
  EXPECT_GT((a.floor_from_pano.translation() - b.floor_from_pano.translation()).norm(), 0.3);
}

TEST(ZindTruthPlan, GivesWallsDoorsAndAreaOfTheBonusRoom) {
  SKIP_WITHOUT_SAMPLE_TOUR();
  const ZindTour tour = ReadZindTour(kSampleTour);
  const ZindPanorama& p = *tour.Find("pano_15");
  const Plan plan = ZindTruthPlan(p);
  ASSERT_EQ(plan.walls.size(), 4u);
  ASSERT_EQ(plan.openings.size(), 3u);
  ASSERT_EQ(plan.rooms.size(), 1u);
  EXPECT_GT(PolygonArea(plan.rooms[0].polygon), 0);  // Counter-clockwise.
  EXPECT_NEAR(plan.rooms[0].area_m2, 15.60, 0.01);
  for (const PlanWall& w : plan.walls) EXPECT_NEAR(*w.height, p.ceiling_height_m, 1e-12);
  // Each door lies on its wall, start nearer the wall's start, widths as annotated.
  const double widths[] = {1.70, 0.81, 0.80};
  for (std::size_t i = 0; i < plan.openings.size(); ++i) {
    const PlanOpening& o = plan.openings[i];
    const PlanWall& w = plan.walls[static_cast<std::size_t>(o.wall)];
    const Vec2 d = (w.end - w.start).normalized();
    EXPECT_LT(std::abs(Cross(d, o.start - w.start)), 1e-3);
    EXPECT_LT(std::abs(Cross(d, o.end - w.start)), 1e-3);
    EXPECT_LT(d.dot(o.start - w.start), d.dot(o.end - w.start));
    EXPECT_NEAR(o.width, widths[i], 0.01);
    EXPECT_EQ(o.kind, OpeningKind::kDoor);
    EXPECT_NEAR(*o.height, p.layout_raw.openings[i].Height(), 1e-9);
  }
  // It is a valid plan.json.
  const fs::path out = fs::temp_directory_path() / "asbuilt_zind_truth.json";
  WritePlan(plan, out);
  EXPECT_EQ(ReadPlan(out).ToString(), plan.ToString());
}

TEST(ZindTruthPlan, KeepsWindowsAndLeavesPassagesOut) {
  SKIP_WITHOUT_SAMPLE_TOUR();
  const ZindTour tour = ReadZindTour(kSampleTour);
  const ZindPanorama& kitchen = *tour.Find("pano_12");  // 1 door, 1 window, 2 passages.
  const Plan plan = ZindTruthPlan(kitchen);
  ASSERT_EQ(plan.openings.size(), 2u);
  EXPECT_EQ(plan.openings[0].kind, OpeningKind::kDoor);
  EXPECT_EQ(plan.openings[1].kind, OpeningKind::kWindow);
  EXPECT_NEAR(*plan.openings[1].sill, 0.95, 0.01);
}

// A minimal tour in a temporary folder, for the error tests.
fs::path WriteTour(const std::string& name, const nlohmann::json& json) {
  const fs::path dir = fs::temp_directory_path() / ("asbuilt_zind_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir / "panos");
  WriteFileAtomic(dir / "panos/p.jpg", "not read");
  WriteFileAtomic(dir / "zind_data.json", json.dump());
  return dir;
}

nlohmann::json MinimalTour() {
  return nlohmann::json::parse(R"({
    "scale_meters_per_coordinate": {"floor_01": 2.0},
    "merger": {"floor_01": {"complete_room_01": {"partial_room_01": {"pano_1": {
      "is_primary": true, "is_inside": true, "camera_height": 1, "ceiling_height": 1.6,
      "image_path": "panos/p.jpg",
      "floor_plan_transformation": {"translation": [0, 0], "rotation": 0, "scale": 0.5},
      "layout_raw": {"vertices": [[-1, -1], [1, -1], [1, 1], [-1, 1]],
                     "doors": [[-0.5, -1], [0.5, -1], [-1, 0.4]], "windows": [], "openings": []}}}}}}})");
}

TEST(ZindTour, ReadsAMinimalTour) {
  const ZindTour tour = ReadZindTour(WriteTour("minimal", MinimalTour()) / "zind_data.json");
  ASSERT_EQ(tour.panoramas.size(), 1u);
  const ZindPanorama& p = tour.panoramas[0];
  EXPECT_DOUBLE_EQ(p.metres_per_unit, 1.0);
  EXPECT_DOUBLE_EQ(p.ceiling_height_m, 1.6);
  ASSERT_EQ(p.layout_raw.openings.size(), 1u);
  const ZindOpening& door = p.layout_raw.openings[0];
  EXPECT_EQ(door.wall, 0);
  EXPECT_DOUBLE_EQ(door.start_m.y(), 1.0);  // Mirrored.
  EXPECT_DOUBLE_EQ(door.bottom_m, 0.0);
  EXPECT_DOUBLE_EQ(door.top_m, 1.4);
  EXPECT_DOUBLE_EQ(ZindTruthPlan(p).rooms[0].area_m2, 4.0);
}

TEST(ZindTour, RejectsBadFieldsWithTheirPaths) {
  nlohmann::json j = MinimalTour();
  nlohmann::json& pano = j["merger"]["floor_01"]["complete_room_01"]["partial_room_01"]["pano_1"];
  pano["layout_raw"]["doors"].push_back({0, 0});
  pano["ceiling_height"] = "high";
  pano["image_path"] = "panos/missing.jpg";
  const fs::path dir = WriteTour("bad", j);
  try {
    ReadZindTour(dir);
    FAIL();
  } catch (const InputError& e) {
    const std::string file = (dir / "zind_data.json").string();
    const std::string at = file + ": merger.floor_01.complete_room_01.partial_room_01.pano_1.";
    ASSERT_EQ(e.problems().size(), 3u) << e.what();
    EXPECT_EQ(e.problems()[0].ToString(), at + "image_path: no such file: " + (dir / "panos/missing.jpg").string());
    EXPECT_EQ(e.problems()[1].ToString(), at + "ceiling_height: expected a number, got \"high\"");
    EXPECT_EQ(e.problems()[2].ToString(),
              at + "layout_raw.doors: expected 3 entries per doors (end A, end B, [bottom z, top z]), got 4 entries");
  }
}

TEST(ZindTour, NamesAMissingFile) {
  try {
    ReadZindTour("/nonexistent/tour");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems()[0].file, "/nonexistent/tour");  // As given: neither a folder nor a file.
  }
}

TEST(ZindReadOptions, DefaultsAreValid) {
  EXPECT_NO_THROW(ZindReadOptions{}.Check());
  EXPECT_THROW(ZindReadOptions{.max_opening_offset_m = -1}.Check(), InvalidArgument);
}

}  // namespace
}  // namespace asbuilt
