#include "asbuilt/formats/points_file.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

TEST(PointsFile, RoundTripsToFiveDecimals) {
  fs::path p = fs::temp_directory_path() / "asbuilt_points_roundtrip.txt";
  std::vector<ClassPoint> points = {{LabelClass::kWall, Vec3(1.234567, -2.5, 1.5), 0.004, PointSource::kCorner, 3},
                                    {LabelClass::kWindow, Vec3(0, 4, 2.1), 0.0, PointSource::kDense, 0},
                                    {LabelClass::kDoor, Vec3(1, 2, 1.0), 0.03, PointSource::kBoundary, 5}};
  WritePoints(points, p);
  std::vector<ClassPoint> back = ReadPoints(p);
  ASSERT_EQ(back.size(), 3u);
  EXPECT_EQ(back[2].source, PointSource::kBoundary);
  EXPECT_EQ(back[0].label, LabelClass::kWall);
  EXPECT_NEAR(back[0].position_m.x(), 1.23457, 1e-9);
  EXPECT_EQ(back[0].source, PointSource::kCorner);
  EXPECT_EQ(back[0].frame, 3);
  EXPECT_EQ(back[1].label, LabelClass::kWindow);
}

TEST(PointsFile, ReadsThePapersFourColumnFormat) {
  fs::path p = fs::temp_directory_path() / "asbuilt_points_paper.txt";
  WriteFileAtomic(p, "wall 1 2 3\n\n# comment\n2 0.5 0.5 1.0\n");
  std::vector<ClassPoint> back = ReadPoints(p);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].label, LabelClass::kDoor);
  EXPECT_EQ(back[1].frame, -1);
  EXPECT_EQ(back[1].source, PointSource::kOther);
}

TEST(PointsFile, BadLinesNameFileAndLine) {
  fs::path p = fs::temp_directory_path() / "asbuilt_points_bad.txt";
  WriteFileAtomic(p, "wall 1 2 3\nroof 1 2 3\nwall 1 x 3\nwall 1\n");
  try {
    ReadPoints(p);
    FAIL();
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 3u);
    EXPECT_EQ(e.problems()[0].ToString(),
              p.string() + ": line 2: unknown class \"roof\" (expected wall, door or window)");
    EXPECT_EQ(e.problems()[1].ToString(), p.string() + ": line 3: column 3: expected a finite number, got \"x\"");
    EXPECT_NE(e.problems()[2].message.find("got 2"), std::string::npos);
  }
}

}  // namespace
}  // namespace asbuilt
