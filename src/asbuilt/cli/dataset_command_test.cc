// `asbuilt dataset mix|check` end to end with the real binary.

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

using testing_util::kData;

fs::path DatasetCommandTestDir() { return testing_util::FreshTestDir("asbuilt_cli_dataset_"); }

TEST(DatasetCommand, MixesRealAndSyntheticAndChecksTheManifest) {
  fs::path rooms = kData / "blender-rooms-public";
  fs::path ade = kData / "ade20k_sceneparsing_samples";
  if (!fs::exists(rooms) || !fs::exists(ade)) GTEST_SKIP() << "shared data not present";
  fs::path dir = DatasetCommandTestDir();
  // Real: the ADE20K samples imported to our labels, beside their images.
  RunResult imp = RunAsbuilt("labels import --format ade20k " + (ade / "annotations").string() + " -o " +
                             (dir / "real/labels").string());
  ASSERT_EQ(imp.exit_code, 0) << imp.out;
  fs::create_directories(dir / "real/images");
  for (const auto& e : fs::directory_iterator(ade / "images")) {
    fs::copy_file(e.path(), dir / "real/images" / e.path().filename());
  }
  // Synthetic: the Blender rooms (left/ + labels/).
  RunResult mix = RunAsbuilt("dataset mix --real " + (dir / "real").string() + " --synthetic " + rooms.string() +
                             " --config RS5050 --total 6 --seed 3 -o " + (dir / "manifest.json").string());
  ASSERT_EQ(mix.exit_code, 0) << mix.out;
  EXPECT_NE(mix.out.find("RS5050 seed 3: 5 train + 1 val"), std::string::npos) << mix.out;
  RunResult v = RunAsbuilt("validate " + (dir / "manifest.json").string());
  EXPECT_EQ(v.exit_code, 0) << v.out;
  EXPECT_NE(v.out.find("ok (manifest)"), std::string::npos) << v.out;
  RunResult check = RunAsbuilt("dataset check " + (dir / "manifest.json").string());
  EXPECT_EQ(check.exit_code, 0) << check.out;
  EXPECT_NE(check.out.find("checked 7 pairs"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("synthetic"), std::string::npos) << check.out;
}

TEST(DatasetCommand, CheckReportsABadPairByNameAndExits1) {
  fs::path dir = DatasetCommandTestDir();
  WriteFileAtomic(dir / "images/a.png", "not an image");
  WriteFileAtomic(dir / "labels/a.png", "not an image");
  RunResult r = RunAsbuilt("dataset check " + dir.string());
  EXPECT_EQ(r.exit_code, 1) << r.out;
  EXPECT_NE(r.out.find("pair a:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("checked 1 pair"), std::string::npos) << r.out;
}

TEST(DatasetCommand, BadConfigIsAUsageError) {
  fs::path dir = DatasetCommandTestDir();
  RunResult r = RunAsbuilt("dataset mix --real " + dir.string() + " --config RS6050 -o " + (dir / "m.json").string());
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("MixOptions.config = \"RS6050\""), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "m.json"));
}

}  // namespace
}  // namespace asbuilt
