#ifndef ASBUILT_REVIEW_REVIEW_TEST_FIXTURES_H_
#define ASBUILT_REVIEW_REVIEW_TEST_FIXTURES_H_

// Surveys the review tests start from (test-only): a panorama of a 4 × 3 m
// box room with exact labels drawn from its geometry (small views: a second
// or two), and the demo classroom rendered as a small stereo capture and
// surveyed with its exact labels. Each is made once per test binary and
// copied fresh for each test.

#include <filesystem>
#include <string>
#include <vector>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/geometry/rig.h"

namespace asbuilt::review_test {

// The box room: x in [−2, 2], y in [−1.5, 1.5], ceiling 2.5 m, camera at
// (0.4, −0.3, 1.4), a 0.9 m door on the north wall from x = −0.6 to 0.3.
inline constexpr double kX0 = -2.0, kX1 = 2.0, kY0 = -1.5, kY1 = 1.5, kCeiling = 2.5;
inline const Vec3 kCamera(0.4, -0.3, 1.4);
inline constexpr int kPanoWidth = 1024, kPanoHeight = 512;

// A fresh copy of the box room's survey output folder (panorama capture).
std::filesystem::path PanoramaSurvey(const std::string& name);
// A fresh copy of the demo classroom's stereo survey output folder, and its truth.
std::filesystem::path ClassroomSurvey(const std::string& name);
Plan ClassroomTruth();

// The panorama pixel of a world point (docs/formats.md).
Vec2 PanoPixel(const Vec3& p);

// An L-shaped room seen from one wing: its corner (0.5, 3.5) is hidden
// behind the wall y = 1.5 (camera at kLCamera, ceiling 2.5 m, exact labels).
std::vector<Vec2> LRoomCorners();
inline const Vec3 kLCamera(-1.0, -0.5, 1.4);
std::filesystem::path LRoomSurvey(const std::string& name);
Vec2 LRoomPanoPixel(const Vec3& p);

}  // namespace asbuilt::review_test

#endif  // ASBUILT_REVIEW_REVIEW_TEST_FIXTURES_H_
