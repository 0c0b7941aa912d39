#include "asbuilt/review/training_example.h"

#include <algorithm>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "asbuilt/dataset/checksum.h"
#include "asbuilt/dataset/manifest.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pano/pano_views.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/review/view_geometry.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

// The label of the plan surface a pixel's ray meets (training_example.h).
std::uint8_t LabelOfPixel(const ReviewImage& image, const Plan& plan, double ceiling_m, const Vec2& pixel) {
  const std::optional<WallHit> hit = WallOfPixel(image, plan, pixel);
  if (!hit) return static_cast<std::uint8_t>(LabelClass::kBackground);
  const double z = HeightAtDistance(image, pixel, hit->distance_m);
  if (z < 0.0 || z > ceiling_m) return static_cast<std::uint8_t>(LabelClass::kBackground);
  for (const PlanOpening& o : plan.openings) {
    if (o.wall != hit->wall) continue;
    const Vec2 along = o.end - o.start;
    const double length = along.norm();
    if (length <= 0) continue;
    const double t = (hit->xy_m - o.start).dot(along) / (length * length);
    const double sill = o.sill.value_or(0.0), head = sill + o.height.value_or(o.kind == OpeningKind::kDoor ? 2.0 : 1.2);
    if (t >= 0 && t <= 1 && z >= sill && z <= head) {
      return static_cast<std::uint8_t>(o.kind == OpeningKind::kDoor ? LabelClass::kDoor : LabelClass::kWindow);
    }
  }
  return static_cast<std::uint8_t>(LabelClass::kWall);
}

// The image the segmenter read for a labelled frame: a panorama's level view
// cut again from the (levelled) panorama, or the frame's own left image.
cv::Mat FrameImage(const ReviewInput& input, const ReviewImage& frame, const std::optional<Image>& panorama) {
  if (panorama) {
    const PanoView view{.camera = frame.camera, .yaw_deg = frame.yaw_deg - input.images.front().yaw_deg};
    return AsMat(RenderPanoView(*panorama, view)).clone();
  }
  const auto own = std::find_if(input.images.begin(), input.images.end(),
                                [&](const ReviewImage& im) { return im.frame == frame.frame; });
  if (own == input.images.end()) {
    throw InputError(input.capture_json.string(), "", fmt::format("frame {} has no image in the survey", frame.frame));
  }
  return ReadColourImage(own->image);
}

}  // namespace

cv::Mat PlanLabels(const ReviewImage& image, const Plan& plan, double ceiling_m) {
  cv::Mat labels(image.height_px, image.width_px, CV_8U);
  for (int v = 0; v < labels.rows; ++v) {
    for (int u = 0; u < labels.cols; ++u)
      labels.at<std::uint8_t>(v, u) = LabelOfPixel(image, plan, ceiling_m, Vec2(u, v));
  }
  return labels;
}

TrainingExample WriteTrainingExample(const ReviewInput& input, const Plan& plan, double ceiling_m,
                                     const fs::path& dir) {
  CheckArgument(!plan.walls.empty(), "a training example needs a plan with walls");
  CheckArgument(std::isfinite(ceiling_m) && ceiling_m > 0,
                fmt::format("a training example needs the ceiling's height, got {}", ceiling_m));
  const bool panorama = input.kind == "panorama";
  std::optional<Image> equirect;
  if (panorama) equirect = ReadEquirect(input.images.front().image);
  TrainingExample out{.dir = dir};
  fs::create_directories(dir / "images");
  fs::create_directories(dir / "labels");
  Manifest manifest{.config = "review", .base_dir = dir};
  for (const ReviewImage& frame : input.labels) {
    const cv::Mat image = FrameImage(input, frame, equirect);
    const std::string ext = panorama ? ".jpg" : fs::path(input.images.front().image).extension().string();
    const std::string image_file = fmt::format("images/{:03d}{}", frame.frame, ext.empty() ? ".png" : ext);
    const std::string label_file = fmt::format("labels/{:03d}.png", frame.frame);
    WriteImageAtomic(dir / image_file, image);
    WriteImageAtomic(dir / label_file, PlanLabels(frame, plan, ceiling_m));
    manifest.train.push_back({.image = image_file,
                              .label = label_file,
                              .source = PairSource::kReal,
                              .sha256 = Sha256OfFile(dir / image_file),
                              .label_sha256 = Sha256OfFile(dir / label_file)});
    out.files.push_back(image_file);
    out.files.push_back(label_file);
    ++out.views;
  }
  WritePlan(plan, dir / "truth.json");
  WriteManifest(manifest, dir / "manifest.json");
  out.files.push_back("truth.json");
  out.files.push_back("manifest.json");
  return out;
}

}  // namespace asbuilt
