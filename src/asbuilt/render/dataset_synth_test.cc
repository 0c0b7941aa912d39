#include "asbuilt/render/dataset_synth.h"

#include <gtest/gtest.h>

#include <filesystem>

#include <fmt/format.h>

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

TEST(ShardRange, ShardsTileTheItemsWithoutOverlap) {
  for (int shards : {1, 3, 7}) {
    int next = 0;
    for (int k = 0; k < shards; ++k) {
      auto [b, e] = ShardRange(20, k, shards);
      EXPECT_EQ(b, next);
      EXPECT_GE(e, b);
      next = e;
    }
    EXPECT_EQ(next, 20);
  }
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

}  // namespace
}  // namespace asbuilt
