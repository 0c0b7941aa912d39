// `asbuilt plan` and `asbuilt eval plan` through the real binary.

#include <cmath>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

using testing_util::RunAsbuilt;
using testing_util::RunResult;

fs::path PlanTempDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("asbuilt_cli_plan_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A 5 × 4 m room as a paper-style point file (`class x y z`), 2 cm apart,
// with a 1 m door on the south wall.
std::string RectangleRoomPoints() {
  std::string text = "# asbuilt points v1\n";
  const double w = 5, h = 4;
  auto wall = [&](double x0, double y0, double x1, double y1) {
    double len = std::hypot(x1 - x0, y1 - y0);
    for (double t = 0; t <= len; t += 0.02) {
      double x = x0 + (x1 - x0) * t / len, y = y0 + (y1 - y0) * t / len;
      bool door = y0 == 0 && y1 == 0 && x > 1.93 && x < 3.07;
      for (double z = 0.1; z < 2.7; z += 0.5) {
        text += fmt::format("{} {:.4f} {:.4f} {:.2f}\n", door && z < 2.1 ? "door" : "wall", x, y, z);
      }
    }
  };
  wall(0, 0, w, 0);
  wall(w, 0, w, h);
  wall(w, h, 0, h);
  wall(0, h, 0, 0);
  return text;
}

TEST(PlanCommand, WritesAllFilesFromAPointFileAndEvalScoresThem) {
  fs::path dir = PlanTempDir("points");
  WriteFileAtomic(dir / "points.txt", RectangleRoomPoints());
  RunResult r = RunAsbuilt(fmt::format("plan {} -o {}", (dir / "points.txt").string(), (dir / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("4 walls (0 inferred), 1 openings, closed, 20.0"), std::string::npos) << r.out;
  for (const char* name : {"plan.json", "plan.svg", "plan.dxf", "plan.pdf", "plan.png", "plan.ifc"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / name)) << name;
  }
  WriteFileAtomic(dir / "truth.json", R"({"version": 1, "units": "m",
    "walls": [{"start": [0, 0], "end": [5, 0]}, {"start": [5, 0], "end": [5, 4]},
              {"start": [5, 4], "end": [0, 4]}, {"start": [0, 4], "end": [0, 0]}],
    "openings": [{"kind": "door", "wall": 0, "start": [2, 0], "end": [3, 0], "width": 1.0}],
    "rooms": [{"polygon": [[0, 0], [5, 0], [5, 4], [0, 4]], "area_m2": 20}]})");
  RunResult e = RunAsbuilt(fmt::format("eval plan {} {} --json {}", (dir / "out/plan.json").string(),
                                       (dir / "truth.json").string(), (dir / "score.json").string()));
  ASSERT_EQ(e.exit_code, 0) << e.out;
  EXPECT_NE(e.out.find("walls              4      4        4   100.0 %    100.0 %"), std::string::npos) << e.out;
  std::string json = ReadFile(dir / "score.json");
  EXPECT_NE(json.find("\"wall_length_relative_error\""), std::string::npos);
}

TEST(PlanCommand, BuildsThePlanFromExactBlenderLabels) {
  fs::path capture = fs::path(ASBUILT_SOURCE_DIR) / "../shared/data/blender-rooms-public/p01_rect_1door_2win";
  if (!fs::exists(capture / "capture.json")) GTEST_SKIP() << "shared data not present";
  fs::path dir = PlanTempDir("capture");
  RunResult r =
      RunAsbuilt(fmt::format("plan {} -o {} --stride-px 6", (capture / "capture.json").string(), dir.string()));
  ASSERT_EQ(r.exit_code, 0) << r.out;
  RunResult e =
      RunAsbuilt(fmt::format("eval plan {} {}", (dir / "plan.json").string(), (capture / "truth.json").string()));
  ASSERT_EQ(e.exit_code, 0) << e.out;
  EXPECT_NE(e.out.find("walls              4      4        4"), std::string::npos) << e.out;
}

TEST(PlanCommand, BadInputNamesTheFileAndExits1WithoutOutput) {
  fs::path dir = PlanTempDir("bad");
  WriteFileAtomic(dir / "points.txt", "wall 1 2\n");
  RunResult r = RunAsbuilt(fmt::format("plan {} -o {}", (dir / "points.txt").string(), (dir / "out").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("points.txt: line 1"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "out" / "plan.json"));
  RunResult missing = RunAsbuilt(fmt::format("plan {} -o {}", (dir / "nope.txt").string(), (dir / "out").string()));
  EXPECT_EQ(missing.exit_code, 1) << missing.out;
  EXPECT_NE(missing.out.find("nope.txt"), std::string::npos) << missing.out;
}

TEST(PlanCommand, UsageErrorsExit2) {
  EXPECT_EQ(RunAsbuilt("plan").exit_code, 2);
  EXPECT_EQ(RunAsbuilt("plan points.txt -o out --epsilon-m -1").exit_code, 2);
  EXPECT_EQ(RunAsbuilt("eval").exit_code, 2);
  EXPECT_EQ(RunAsbuilt("eval plan only_one.json").exit_code, 2);
}

TEST(EvalCommand, BadPlanFileNamesTheFieldAndExits1) {
  fs::path dir = PlanTempDir("eval_bad");
  WriteFileAtomic(dir / "plan.json", R"({"version": 1, "walls": [{"start": [0, 0], "end": "x"}]})");
  RunResult r = RunAsbuilt(fmt::format("eval plan {0} {0}", (dir / "plan.json").string()));
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("walls[0].end"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace asbuilt
