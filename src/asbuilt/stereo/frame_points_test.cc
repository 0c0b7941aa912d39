#include "asbuilt/stereo/frame_points.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace {
namespace fs = std::filesystem;

fs::path RoomDir(const std::string& room) {
  return fs::path(ASBUILT_SHARED_DATA_DIR) / "blender-rooms-public" / room;
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1))];
}

// Truth z-depth (m) at a pixel from the room's depth map, taken over the
// pixels of `label` within 2 px (a corner sits on its region's border).
double TruthDepth(const cv::Mat& depth_mm, const cv::Mat& labels, const Vec2& px, int label) {
  std::vector<double> z;
  const int cu = static_cast<int>(std::lround(px.x())), cv_ = static_cast<int>(std::lround(px.y()));
  for (int y = std::max(0, cv_ - 2); y <= std::min(depth_mm.rows - 1, cv_ + 2); ++y) {
    for (int x = std::max(0, cu - 2); x <= std::min(depth_mm.cols - 1, cu + 2); ++x) {
      if (labels.at<unsigned char>(y, x) == label && depth_mm.at<unsigned short>(y, x) > 0) {
        z.push_back(depth_mm.at<unsigned short>(y, x) / 1000.0);
      }
    }
  }
  return Percentile(z, 0.5);
}

struct RoomFrames {
  Capture capture;
  std::vector<StereoFrame> frames;
  std::vector<cv::Mat> depth_mm;
};

RoomFrames LoadRoom(const std::string& room, const std::vector<int>& indices) {
  RoomFrames r;
  r.capture = ReadCapture(RoomDir(room) / "capture.json");
  const LabelProvider labels = LabelsFromCapture(r.capture);
  for (int i : indices) {
    const CaptureFrame& f = r.capture.frames.at(i);
    r.frames.push_back(LoadStereoFrame(r.capture, f, labels, nullptr));
    r.depth_mm.push_back(cv::imread(r.capture.Resolve(*f.depth).string(), cv::IMREAD_UNCHANGED));
  }
  return r;
}

TEST(ComputeFramePoints, MatchedCornersAgreeWithRenderedDepth) {
  RoomFrames room = LoadRoom("p01_rect_1door_2win", {0, 1, 3, 5, 8});
  std::vector<double> disparity_error, relative_error;
  for (std::size_t i = 0; i < room.frames.size(); ++i) {
    const StereoFrame& f = room.frames[i];
    FramePointsResult r = ComputeFramePoints(f, {});
    std::printf("%s\n", r.cues.BriefReport().c_str());
    for (const MatchedCorner& c : r.corners) {
      const double z = TruthDepth(room.depth_mm[i], f.labels_left, c.corner.pixel, static_cast<int>(c.corner.label));
      if (!std::isfinite(z)) continue;
      const double d_truth = f.camera.fx * f.baseline_m / z;
      disparity_error.push_back(std::abs(c.match.disparity_px - d_truth));
      const double z_est = f.camera.fx * f.baseline_m / c.match.disparity_px;
      if (z >= 2 && z <= 6) relative_error.push_back(std::abs(z_est - z) / z);
    }
  }
  std::printf("corners %zu: disparity error median %.3f p95 %.3f; depth error (2-6 m) median %.4f p90 %.4f\n",
              disparity_error.size(), Percentile(disparity_error, 0.5), Percentile(disparity_error, 0.95),
              Percentile(relative_error, 0.5), Percentile(relative_error, 0.9));
  ASSERT_GE(disparity_error.size(), 20u);
  EXPECT_LE(Percentile(disparity_error, 0.5), 0.25);
  EXPECT_LE(Percentile(disparity_error, 0.95), 1.0);
  EXPECT_LE(Percentile(relative_error, 0.5), 0.01);
}

}  // namespace
}  // namespace asbuilt
