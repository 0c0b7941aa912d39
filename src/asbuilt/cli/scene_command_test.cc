// `asbuilt scene …` end to end through the real binary.

#include <unistd.h>

#include <filesystem>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing_util::RunAsbuilt;
using testing_util::RunResult;

fs::path SceneTempDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("asbuilt_cli_scene_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(SceneCommand, TextToSceneToTruthGivesTheIssueExample) {
  fs::path dir = SceneTempDir("text");
  RunResult r = RunAsbuilt(
      "scene text \"a 6 by 8 m classroom, 3 m high, with a 1 m wide door on the east wall and two 1.5 m "
      "windows on the north wall\" -o " +
      (dir / "scene.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("classroom: 6.00 × 8.00 m, 3 openings, 12 views"));
  r = RunAsbuilt("scene truth " + (dir / "scene.json").string() + " -o " + (dir / "truth.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  nlohmann::json truth = nlohmann::json::parse(ReadFile(dir / "truth.json"));
  ASSERT_EQ(truth["walls"].size(), 4u);
  EXPECT_EQ(truth["rooms"][0]["area_m2"], 48.0);
  ASSERT_EQ(truth["openings"].size(), 3u);
  EXPECT_EQ(truth["openings"][0]["kind"], "door");
  EXPECT_EQ(truth["openings"][0]["width"], 1.0);
  EXPECT_EQ(truth["openings"][0]["start"][0], 6.0);  // East wall: x = 6.
  for (int i : {1, 2}) {
    EXPECT_EQ(truth["openings"][i]["kind"], "window");
    EXPECT_EQ(truth["openings"][i]["width"], 1.5);
    EXPECT_EQ(truth["openings"][i]["start"][1], 8.0);  // North wall: y = 8.
  }
  r = RunAsbuilt("validate " + (dir / "scene.json").string() + " " + (dir / "truth.json").string());
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("scene.json: ok (scene)"));
  EXPECT_THAT(r.out, HasSubstr("truth.json: ok (plan)"));
}

TEST(SceneCommand, TextReportsUnusedWords) {
  fs::path dir = SceneTempDir("unused");
  RunResult r = RunAsbuilt("scene text \"a bedroom with a purple giraffe\" -o " + (dir / "s.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("2 words not understood: \"purple\", \"giraffe\""));
}

TEST(SceneCommand, ImpossibleTextExits1WithoutOutput) {
  fs::path dir = SceneTempDir("impossible");
  RunResult r = RunAsbuilt("scene text \"a 3 by 3 m room with six 1 m windows on the north wall\" -o " +
                           (dir / "s.json").string());
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_THAT(r.out, HasSubstr("north wall (3.00 m) cannot hold 6 openings"));
  EXPECT_FALSE(fs::exists(dir / "s.json"));
}

TEST(SceneCommand, RandomWritesValidScenes) {
  fs::path dir = SceneTempDir("random");
  RunResult r = RunAsbuilt("scene random --seed 5 --count 3 -o " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("3 scenes in "));
  RunResult v = RunAsbuilt("validate " + (dir / "scene_0000.json").string() + " " + (dir / "scene_0001.json").string() +
                           " " + (dir / "scene_0002.json").string());
  EXPECT_EQ(v.exit_code, 0) << v.out;
  EXPECT_THAT(v.out, HasSubstr("scene_0002.json: ok (scene)"));
  fs::path again = SceneTempDir("random_again");
  ASSERT_EQ(RunAsbuilt("scene random --seed 6 --count 1 -o " + again.string()).exit_code, 0);
  EXPECT_EQ(ReadFile(dir / "scene_0001.json"), ReadFile(again / "scene_0000.json"));
  EXPECT_EQ(RunAsbuilt("scene random --count 0 -o " + dir.string()).exit_code, 2);
}

TEST(SceneCommand, DescribeAndExportBlender) {
  fs::path dir = SceneTempDir("describe");
  std::string example = std::string(ASBUILT_SOURCE_DIR) + "/examples/classroom.json";
  RunResult r = RunAsbuilt("scene describe " + example);
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("6.00 × 8.00 m room (48.00 m²), 3.00 m high, 1 door, 2 windows"));
  r = RunAsbuilt("scene export-blender " + example + " -o " + (dir / "build.py").string());
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_THAT(r.out, HasSubstr("12 frames"));
  EXPECT_THAT(ReadFile(dir / "build.py"), HasSubstr("import bpy"));
}

TEST(SceneCommand, BadSceneFileNamesTheField) {
  fs::path dir = SceneTempDir("bad");
  WriteFileAtomic(dir / "bad.json",
                  R"({"version": 1, "rooms": [{"polygon": [[0, 0], [4, 0], [4, 4], [0, 4]],
                      "openings": [{"kind": "door", "wall": 9}]}]})");
  RunResult r = RunAsbuilt("scene truth " + (dir / "bad.json").string() + " -o " + (dir / "t.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.out, HasSubstr("bad.json: rooms[0].openings[0].wall: wall index 9 out of range (room has 4 walls)"));
  EXPECT_FALSE(fs::exists(dir / "t.json"));
  r = RunAsbuilt("validate " + (dir / "bad.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.out, HasSubstr("invalid (1 problem)"));
}

TEST(SceneCommand, LlmEndpointDownIsAClearError) {
  fs::path dir = SceneTempDir("llm");
  RunResult r = RunAsbuilt("scene text \"an office\" --llm http://127.0.0.1:9/v1 --llm-timeout 2 -o " +
                           (dir / "s.json").string());
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_THAT(r.out, HasSubstr("LLM endpoint http://127.0.0.1:9/v1/chat/completions"));
  EXPECT_FALSE(fs::exists(dir / "s.json"));
  EXPECT_EQ(RunAsbuilt("scene text \"an office\" --llm ftp://x -o " + (dir / "s.json").string()).exit_code, 2);
}

TEST(SceneCommand, SchemaAndUsageErrors) {
  RunResult r = RunAsbuilt("scene schema");
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("\"$schema\": \"https://json-schema.org/draft/2020-12/schema\""));
  EXPECT_EQ(RunAsbuilt("scene").exit_code, 2);
  EXPECT_EQ(RunAsbuilt("scene frobnicate").exit_code, 2);
  EXPECT_EQ(RunAsbuilt("scene text").exit_code, 2);
}

}  // namespace
}  // namespace asbuilt
