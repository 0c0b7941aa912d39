// `asbuilt labels …` end to end: the real binary on small generated files
// and on the shared ADE20K / NYUv2 samples.

#include <cstdio>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "asbuilt/cli/cli_test_util.h"
#include "asbuilt/labels/idmap_synth.h"
#include "asbuilt/labels/label_io.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

using testing_util::RunAsbuilt;
using testing_util::RunResult;

using testing_util::kData;

fs::path LabelsCommandTestDir() { return testing_util::FreshTestDir("asbuilt_cli_labels_"); }

TEST(LabelsCommand, ImportsAde20kAndNyuSamples) {
  fs::path ade = kData / "ade20k_sceneparsing_samples/annotations";
  if (!fs::exists(ade)) GTEST_SKIP() << "shared data not present";
  fs::path dir = LabelsCommandTestDir();
  RunResult r = RunAsbuilt("labels import --format ade20k " + ade.string() + " -o " + (dir / "ade").string());
  EXPECT_EQ(r.exit_code, 0) << r.out;
  EXPECT_NE(r.out.find("imported 4 ade20k annotations"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "ade/ADE_val_00001519.png"));
  RunResult n = RunAsbuilt("labels import --format nyuv2 " + (kData / "nyuv2_sample/semantic40_ids.png").string() +
                           " -o " + (dir / "nyu").string());
  EXPECT_EQ(n.exit_code, 0) << n.out;
  EXPECT_TRUE(fs::exists(dir / "nyu/semantic40_ids.png"));
  // The imported maps are valid label maps: compare one with itself.
  RunResult c = RunAsbuilt("labels compare " + (dir / "ade").string() + " " + (dir / "ade").string());
  EXPECT_EQ(c.exit_code, 0) << c.out;
  EXPECT_NE(c.out.find("agreement 100.00 %"), std::string::npos) << c.out;
}

TEST(LabelsCommand, BadInputInABatchIsNamedAndTheRestConverted) {
  if (!fs::exists(kData / "nyuv2_sample")) GTEST_SKIP() << "shared data not present";
  fs::path dir = LabelsCommandTestDir();
  RunResult imp = RunAsbuilt("labels import --format nyuv2 " + (kData / "nyuv2_sample/semantic40_ids.png").string() +
                             " " + (dir / "missing.png").string() + " -o " + (dir / "out").string());
  EXPECT_EQ(imp.exit_code, 1) << imp.out;
  EXPECT_NE(imp.out.find((dir / "missing.png").string() + ": cannot read"), std::string::npos) << imp.out;
  EXPECT_TRUE(fs::exists(dir / "out/semantic40_ids.png"));
}

TEST(LabelsCommand, CalibrateConvertCompareReachTheTarget) {
  fs::path dir = LabelsCommandTestDir();
  for (int i = 0; i < 4; ++i) {
    cv::Mat labels = SyntheticRoomLabels(320, 240, 40 + i);
    WriteLabelImage(dir / fmt::format("masks/{:03d}.png", i), labels);
    WriteImageAtomic(dir / fmt::format("idmap/{:03d}.png", i),
                     SynthesizeIdMap(labels, Palette::Nominal(), {.seed = static_cast<std::uint64_t>(i)}));
  }
  RunResult cal = RunAsbuilt("labels calibrate --idmaps " + (dir / "idmap").string() + " --masks " +
                             (dir / "masks").string() + " -o " + (dir / "palette.json").string());
  ASSERT_EQ(cal.exit_code, 0) << cal.out;
  EXPECT_NE(cal.out.find("calibrated 4 ID maps by masks"), std::string::npos) << cal.out;
  RunResult v = RunAsbuilt("validate " + (dir / "palette.json").string());
  EXPECT_NE(v.out.find("ok (palette)"), std::string::npos) << v.out;
  RunResult conv = RunAsbuilt("labels convert --palette " + (dir / "palette.json").string() + " " +
                              (dir / "idmap").string() + " -o " + (dir / "out").string());
  ASSERT_EQ(conv.exit_code, 0) << conv.out;
  EXPECT_NE(conv.out.find("converted 4 ID maps"), std::string::npos) << conv.out;
  RunResult cmp = RunAsbuilt("labels compare " + (dir / "out").string() + " " + (dir / "masks").string());
  ASSERT_EQ(cmp.exit_code, 0) << cmp.out;
  double agreement = 0;
  ASSERT_EQ(std::sscanf(cmp.out.c_str() + cmp.out.find("agreement ") + 10, "%lf", &agreement), 1) << cmp.out;
  EXPECT_GE(agreement, 99.5) << cmp.out;
  RunResult bad =
      RunAsbuilt("labels convert --threshold -3 " + (dir / "idmap").string() + " -o " + (dir / "out2").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.out;
  EXPECT_NE(bad.out.find("ConvertOptions.threshold = -3"), std::string::npos) << bad.out;
}

TEST(LabelsCommand, UnknownFormatIsAUsageError) {
  RunResult r = RunAsbuilt("labels import --format coco x -o y");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_NE(r.out.find("unknown format 'coco'"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace asbuilt
