// Runs the real `asbuilt` binary and checks exit codes and messages.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

using testing_util::RunAsbuilt;
using testing_util::RunResult;

TEST(Cli, HelpListsTheCommands) {
  RunResult r = RunAsbuilt("help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("validate"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("usage: asbuilt <command>"), std::string::npos);
}

TEST(Cli, UnknownCommandListsCommandsAndExits2) {
  RunResult r = RunAsbuilt("frobnicate");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("unknown command 'frobnicate'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("validate"), std::string::npos);
}

TEST(Cli, CommandHelpExits0) {
  RunResult r = RunAsbuilt("validate --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--kind"), std::string::npos) << r.out;
  RunResult h = RunAsbuilt("help validate");
  EXPECT_EQ(h.exit_code, 0);
  EXPECT_NE(h.out.find("--kind"), std::string::npos) << h.out;
}

TEST(Cli, BadFlagIsAUsageError) {
  RunResult r = RunAsbuilt("validate --no-such-flag x.json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.out.find("--help"), std::string::npos) << r.out;
}

TEST(Cli, ValidateMalformedCaptureExits1WithFieldPath) {
  fs::path dir = fs::temp_directory_path() / "asbuilt_cli_validate";
  fs::remove_all(dir);
  WriteFileAtomic(dir / "l.png", "x");
  WriteFileAtomic(dir / "capture.json", R"({"version": 1,
    "camera": {"width": 640, "height": 480, "fx": 400, "fy": 400, "cx": 319.5, "cy": 239.5, "baseline_m": 0.12},
    "rectified": true,
    "frames": [{"index": 0, "left": "l.png", "right": "l.png", "yaw_deg": "abc", "position_m": [0, 0, 1.5]},
               {"index": 0, "left": "l.png", "right": "l.png", "yaw_deg": 0, "position_m": [0, 0]}]})");
  RunResult r = RunAsbuilt("validate " + (dir / "capture.json").string());
  EXPECT_EQ(r.exit_code, 1);
  std::string file = (dir / "capture.json").string();
  EXPECT_NE(r.out.find(file + ": frames[0].yaw_deg: expected a number, got \"abc\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(file + ": frames[1].index: duplicate frame index 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(file + ": frames[1].position_m: expected 3 elements, got 2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("invalid (3 problems)"), std::string::npos) << r.out;
}

TEST(Cli, ValidateAcceptsBlenderRoomsFiles) {
  fs::path room = fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public/p01_rect_1door_2win";
  if (!fs::exists(room)) GTEST_SKIP() << "shared data not present";
  RunResult r = RunAsbuilt("validate " + (room / "capture.json").string() + " " + (room / "truth.json").string());
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("ok (capture)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ok (plan)"), std::string::npos) << r.out;
}

TEST(Cli, ValidateMissingFileExits1NamingIt) {
  RunResult r = RunAsbuilt("validate /nonexistent/plan.json");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("/nonexistent/plan.json: cannot read: No such file or directory"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace asbuilt
