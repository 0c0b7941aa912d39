#include "asbuilt/render/dataset_synth.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include <fmt/format.h>

#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

DatasetSynthOptions TinyOptions() {
  DatasetSynthOptions o;
  o.count = 6;
  o.seed = 11;
  o.width_px = 64;
  o.height_px = 48;
  o.items_per_scene = 3;
  o.render.samples_per_pixel = 1;
  return o;
}

TEST(DatasetSynthOptions, DefaultsAreValid) { EXPECT_NO_THROW(DatasetSynthOptions{}.Check()); }

TEST(DatasetSynthOptions, RejectsAShardOutsideTheCount) {
  DatasetSynthOptions o;
  o.shard_index = 2;
  o.shard_count = 2;
  EXPECT_THROW(o.Check(), InvalidArgument);
}

TEST(PlanSynthItem, PhotoViewsStandInsideTheRoomFacingTheirTarget) {
  DatasetSynthOptions o = TinyOptions();
  Scene scene = RandomScene(o.scene, 5);
  int photos = 0;
  for (int i = 0; i < 40; ++i) {
    SynthItem item = PlanSynthItem(o, scene, i);
    const Vec3& p = item.camera.viewpoint.position_m;
    EXPECT_GT(p.z(), 0.3);
    EXPECT_LT(p.z(), scene.rooms[0].height_m);
    if (item.kind == "photo") {
      ++photos;
      EXPECT_LE(std::abs(item.camera.viewpoint.pitch_deg), 35.0);
    } else {
      EXPECT_EQ(item.camera.viewpoint.pitch_deg, 0.0);
    }
  }
  EXPECT_GT(photos, 20);
}

TEST(PlanSynthItem, CloseViewsFillTheFrameWithWallAndLeaveOtherItemsAlone) {
  DatasetSynthOptions off = TinyOptions(), on = TinyOptions();
  on.levers.close_views = true;
  int close = 0, corners = 0, pitched = 0, ceiling_on_top = 0;
  double wall_fraction = 0.0;
  for (std::uint64_t seed = 0; seed < 6; ++seed) {
    Scene scene = RandomScene(on.scene, seed);
    SceneRenderer renderer(scene);
    for (int i = 0; i < 20; ++i) {
      SynthItem a = PlanSynthItem(off, scene, i), b = PlanSynthItem(on, scene, i);
      if (b.target != "close_wall" && b.target != "corner") {
        EXPECT_EQ(a.camera.viewpoint.position_m, b.camera.viewpoint.position_m);  // Not chosen: as before.
        continue;
      }
      ++close;
      corners += b.target == "corner";
      EXPECT_EQ(b.kind, "photo");
      EXPECT_GE(b.camera.viewpoint.pitch_deg, -5.0);
      EXPECT_LE(b.camera.viewpoint.pitch_deg, 45.0);
      RenderedView v = renderer.Render(b.camera, {.samples_per_pixel = 1, .camera_effects = 0.0}, i, false);
      const cv::Mat labels = AsMat(v.labels);
      wall_fraction += cv::countNonZero(labels == kLabelWall) / static_cast<double>(labels.total());
      if (b.camera.viewpoint.pitch_deg > 5.0) {
        // Pitched up: the ceiling (background) is in the top row, the wall below it.
        ++pitched;
        ceiling_on_top += cv::countNonZero(labels.row(0) == kLabelBackground) > labels.cols / 2;
      }
    }
  }
  EXPECT_GT(close, 20);  // 30 % of 120.
  EXPECT_GT(corners, 3);
  EXPECT_GT(wall_fraction / close, 0.6) << "mean wall share of a close view";
  EXPECT_GT(ceiling_on_top, pitched * 3 / 4);
  std::printf("close views: %d (%d corners, %d pitched up, %d with the ceiling on top), mean wall share %.3f\n", close,
              corners, pitched, ceiling_on_top, wall_fraction / close);
}

// close_doors: a fifth of the views stand close to a door and see much of
// it (door label); the other items are as without the lever.
TEST(PlanSynthItem, CloseDoorViewsSeeMuchDoorAndLeaveOtherItemsAlone) {
  DatasetSynthOptions off = TinyOptions(), on = TinyOptions();
  on.levers.close_doors = true;
  int close = 0, rooms_with_doors = 0;
  double door_fraction = 0.0;
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    Scene scene = RandomScene(on.scene, seed);
    bool has_door = false;
    for (const Opening& o : scene.rooms[0].openings) has_door |= o.kind == OpeningKind::kDoor;
    rooms_with_doors += has_door;
    SceneRenderer renderer(scene);
    for (int i = 0; i < 20; ++i) {
      SynthItem a = PlanSynthItem(off, scene, i), b = PlanSynthItem(on, scene, i);
      if (b.target != "close_door") {
        EXPECT_EQ(a.camera.viewpoint.position_m, b.camera.viewpoint.position_m);  // Not chosen: as before.
        continue;
      }
      ASSERT_TRUE(has_door);
      ++close;
      EXPECT_EQ(b.kind, "photo");
      EXPECT_LE(std::abs(b.camera.viewpoint.pitch_deg), 10.0);
      RenderedView v = renderer.Render(b.camera, {.samples_per_pixel = 1, .camera_effects = 0.0}, i, false);
      const cv::Mat labels = AsMat(v.labels);
      door_fraction += cv::countNonZero(labels == kLabelDoor) / static_cast<double>(labels.total());
    }
  }
  ASSERT_GT(rooms_with_doors, 3);
  EXPECT_GT(close, rooms_with_doors * 20 / 10);  // 20 % of the rooms-with-doors' views, less misses.
  EXPECT_GT(door_fraction / close, 0.25) << "mean door share of a close door view";
  std::printf("close door views: %d in %d rooms with doors, mean door share %.3f\n", close, rooms_with_doors,
              door_fraction / close);
}

TEST(SynthesizeDataset, ShardUnionEqualsTheWholeRunAndResumes) {
  fs::path root = fs::path(ASBUILT_BINARY_DIR) / "render_test_synth";
  fs::remove_all(root);
  DatasetSynthOptions o = TinyOptions();
  DatasetSynthSummary whole = SynthesizeDataset(root / "whole", o);
  EXPECT_EQ(whole.rendered, 6);
  EXPECT_EQ(whole.scenes, 2);
  for (int k = 0; k < 2; ++k) {
    DatasetSynthOptions s = o;
    s.shard_index = k;
    s.shard_count = 2;
    EXPECT_EQ(SynthesizeDataset(root / "shards", s).rendered, 3);
  }
  int compared = 0;
  for (const char* sub : {"images", "labels", "idmaps", "depth", "meta"}) {
    for (int i = 0; i < 6; ++i) {
      std::string name = fmt::format("{:06d}.{}", i, std::string(sub) == "meta" ? "json" : "png");
      EXPECT_EQ(ReadFile(root / "whole" / sub / name), ReadFile(root / "shards" / sub / name)) << sub << "/" << name;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 30);

  fs::remove(root / "whole" / "meta" / "000004.json");
  DatasetSynthSummary again = SynthesizeDataset(root / "whole", o);
  EXPECT_EQ(again.rendered, 1);
  EXPECT_EQ(again.skipped, 5);
  EXPECT_NE(again.BriefReport().find("rendered 1 of 6 items"), std::string::npos);
}

TEST(ParseSynthLevers, ReadsAllNoneAndListsAndNamesAnUnknownLever) {
  EXPECT_EQ(ParseSynthLevers("none").ToString(), "none");
  EXPECT_EQ(ParseSynthLevers("all").ToString(),
            "photo_textures,outside_photos,next_rooms,door_leaves,home_palette,sunlight,kitchens,wall_details,"
            "window_dressing,phone_camera,glass_doors,close_views,ceiling_like_walls,wall_art,close_doors");
  EXPECT_EQ(ParseSynthLevers("all,-sunlight,-phone_camera,-wall_art,-close_doors").ToString(),
            "photo_textures,outside_photos,next_rooms,door_leaves,home_palette,kitchens,wall_details,"
            "window_dressing,glass_doors,close_views,ceiling_like_walls");
  EXPECT_EQ(ParseSynthLevers("kitchens,door_leaves").ToString(), "door_leaves,kitchens");
  try {
    ParseSynthLevers("kitchens,skylights");
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("\"skylights\""), std::string::npos) << e.what();
  }
  EXPECT_FALSE(SynthLevers{}.Any());
}

TEST(SynthesizeDataset, LeversRenderValidItemsWithPhotosFromAFolder) {
  const fs::path photos = fs::temp_directory_path() / fmt::format("asbuilt_synth_photos_{}", ::getpid());
  const fs::path dir = fs::temp_directory_path() / fmt::format("asbuilt_synth_levers_{}", ::getpid());
  fs::remove_all(photos);
  fs::remove_all(dir);
  fs::create_directories(photos / "backgrounds");
  // Tiny generated textures (never real photos in tests): stripes for wood, noise for paper.
  cv::Mat wood(32, 32, CV_8UC3), paper(32, 32, CV_8UC3);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 32; ++x) {
      wood.at<cv::Vec3b>(y, x) = cv::Vec3b(40, 80 + 4 * (y % 8), 140 + 6 * (y % 8));
      paper.at<cv::Vec3b>(y, x) = cv::Vec3b::all(static_cast<std::uint8_t>(200 + (x * 7 + y * 13) % 40));
    }
  }
  cv::imwrite((photos / "oak_wood.png").string(), wood);
  cv::imwrite((photos / "paper.png").string(), paper);
  cv::imwrite((photos / "backgrounds" / "garden.png").string(), cv::Mat(16, 32, CV_8UC3, cv::Scalar(60, 160, 90)));
  DatasetSynthOptions o = TinyOptions();
  o.levers = ParseSynthLevers("all");
  o.photo_dirs = {photos};
  DatasetSynthSummary summary = SynthesizeDataset(dir, o);
  EXPECT_EQ(summary.rendered, 6);
  for (int i = 0; i < 6; ++i) {
    const cv::Mat labels = ReadLabelImage(dir / "labels" / fmt::format("{:06d}.png", i));
    double lo, hi;
    cv::minMaxLoc(labels, &lo, &hi);
    EXPECT_LE(hi, 3.0);
    std::string meta = ReadFile(dir / "meta" / fmt::format("{:06d}.json", i));
    EXPECT_NE(meta.find("\"levers\""), std::string::npos);
    EXPECT_NE(meta.find("garden.png"), std::string::npos) << meta;  // The view outside.
  }
  fs::remove_all(photos);
  fs::remove_all(dir);
}

TEST(SynthesizeDataset, LeversOffWriteTheItemsAsBefore) {
  // Same options, levers off, photo folders irrelevant: identical bytes.
  const fs::path a = fs::temp_directory_path() / fmt::format("asbuilt_synth_off_a_{}", ::getpid());
  const fs::path b = fs::temp_directory_path() / fmt::format("asbuilt_synth_off_b_{}", ::getpid());
  DatasetSynthOptions o = TinyOptions();
  o.count = 2;
  SynthesizeDataset(a, o);
  o.photo_dirs = {};
  SynthesizeDataset(b, o);
  for (const char* file : {"images/000001.png", "labels/000001.png", "meta/000001.json"}) {
    EXPECT_EQ(ReadFile(a / file), ReadFile(b / file)) << file;
  }
  fs::remove_all(a);
  fs::remove_all(b);
}

}  // namespace
}  // namespace asbuilt
