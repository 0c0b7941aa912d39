#include <gtest/gtest.h>

#include <filesystem>

#include "asbuilt/cli/cli_test_util.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
using testing_util::RunAsbuilt;

const std::string kClassroom = std::string(ASBUILT_SOURCE_DIR) + "/examples/classroom.json";

TEST(RenderCommand, RendersACaptureThatValidates) {
  fs::path out = fs::path(ASBUILT_BINARY_DIR) / "cli_render_capture";
  fs::remove_all(out);
  auto r = RunAsbuilt("render " + kClassroom + " -o " + out.string() + " --views 2 --size 64x48 --spp 1");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("rendered 2 of 2 views"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(out / "depth" / "001.png"));
  auto v = RunAsbuilt("validate " + (out / "capture.json").string() + " " + (out / "truth.json").string());
  EXPECT_EQ(v.exit_code, 0) << v.out;
}

TEST(RenderCommand, BadSizeIsAUsageError) {
  auto r = RunAsbuilt("render " + kClassroom + " -o /tmp/never --size big");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("--size"), std::string::npos) << r.out;
}

TEST(RenderCommand, MissingSceneFailsNamingTheFile) {
  auto r = RunAsbuilt("render /nonexistent/scene.json -o /tmp/never");
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("/nonexistent/scene.json"), std::string::npos) << r.out;
}

TEST(DatasetSynthCommand, WritesItemsAndSkipsThemOnRerun) {
  fs::path out = fs::path(ASBUILT_BINARY_DIR) / "cli_dataset_synth";
  fs::remove_all(out);
  auto r = RunAsbuilt("dataset synth -o " + out.string() + " --count 3 --size 48x36 --spp 1 --seed 4");
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_TRUE(fs::exists(out / "images" / "000002.png"));
  EXPECT_TRUE(fs::exists(out / "meta" / "000002.json"));
  auto again = RunAsbuilt("dataset synth -o " + out.string() + " --count 3 --size 48x36 --spp 1 --seed 4");
  ASSERT_EQ(again.exit_code, 0) << again.out;
  EXPECT_NE(again.out.find("rendered 0 of 3 items (3 already done"), std::string::npos) << again.out;
}

TEST(DatasetSynthCommand, BadShardIsAUsageError) {
  auto r = RunAsbuilt("dataset synth -o /tmp/never --shard 3/2");
  EXPECT_EQ(r.exit_code, 2) << r.out;
}

}  // namespace
}  // namespace asbuilt
