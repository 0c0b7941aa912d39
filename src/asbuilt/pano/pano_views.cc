#include "asbuilt/pano/pano_views.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pano/layout_labels.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"
#include "asbuilt/util/text.h"

namespace asbuilt {
namespace fs = std::filesystem;

void PanoViewsOptions::Check() const {
  turn.Check();
  if (camera_height_m) {
    CheckArgument(std::isfinite(*camera_height_m) && *camera_height_m > 0,
                  fmt::format("PanoViewsOptions.camera_height_m = {}, must be > 0", *camera_height_m));
  }
}

std::string PanoViewsSummary::BriefReport() const {
  return fmt::format("{} view{}{}{} → {}", views, views == 1 ? "" : "s",
                     labels ? (truth ? " + layout labels" : " + labels") : "", truth ? " + truth.json" : "",
                     views_json.string());
}

Image ReadEquirect(const fs::path& path) {
  const cv::Mat image = ReadColourImage(path);
  if (std::abs(image.cols - 2 * image.rows) > 1) {
    throw InputError(
        path.string(), "",
        fmt::format("{}x{} is not an equirectangular panorama (twice as wide as high)", image.cols, image.rows));
  }
  return AsImage(image);
}

Image ReadLabelEquirect(const fs::path& path) {
  const std::string ext = AsciiLower(path.extension().string());
  cv::Mat labels;
  if (ext == ".exr") {
    AllowOpenExr();  // A label pass the user names.
    const cv::Mat stored = ReadImageAsStored(path);
    cv::Mat first;
    cv::extractChannel(stored, first, 0);
    first.convertTo(first, CV_32F);
    labels.create(first.rows, first.cols, CV_8UC1);
    for (int y = 0; y < first.rows; ++y) {
      for (int x = 0; x < first.cols; ++x) {
        const float value = first.at<float>(y, x);
        const long id = std::lround(value);
        if (!(std::abs(value - id) < 0.01f) || !((id >= 0 && id <= 3) || id == 255)) {
          throw InputError(path.string(), "",
                           fmt::format("pixel ({}, {}) holds {}, not a label id (0 other, 1 wall, 2 door, 3 "
                                       "window, 255 ignore)",
                                       x, y, value));
        }
        labels.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(id);
      }
    }
  } else {
    labels = ReadLabelImage(path);
  }
  if (std::abs(labels.cols - 2 * labels.rows) > 1) {
    throw InputError(path.string(), "",
                     fmt::format("{}x{} is not an equirectangular label panorama (twice as wide as high)", labels.cols,
                                 labels.rows));
  }
  return AsImage(labels);
}

PanoViewsSummary WritePanoViews(const fs::path& panorama, const fs::path& out_dir, const PanoViewsOptions& options,
                                const ZindPanorama* zind, const ProgressCallback& progress) {
  options.Check();
  const std::vector<PanoView> views = TurnInPlaceViews(options.turn);
  const Image equirect = ReadEquirect(panorama);
  std::optional<double> height = options.camera_height_m;
  if (!height && zind) height = zind->camera_height_m;
  if (zind) zind->Layout(options.layout);  // Throws now if the layout is missing.
  CheckArgument(!(zind && !options.label_panorama.empty()),
                "PanoViewsOptions.label_panorama: a ZInD panorama has its own layout labels");
  std::optional<Image> label_equirect;
  if (!options.label_panorama.empty()) label_equirect = ReadLabelEquirect(options.label_panorama);

  fs::create_directories(out_dir);
  const PinholeCamera& cam = views.front().camera;
  nlohmann::json frames = nlohmann::json::array();
  for (std::size_t i = 0; i < views.size(); ++i) {
    const PanoView& view = views[i];
    const std::string name = fmt::format("{:03d}.png", i);
    const Image image = RenderPanoView(equirect, view);
    WriteImageAtomic(out_dir / "images" / name, image);
    nlohmann::json frame = {
        {"index", i}, {"image", "images/" + name}, {"yaw_deg", view.yaw_deg}, {"pitch_deg", view.pitch_deg}};
    if (height) frame["position_m"] = {0.0, 0.0, *height};
    if (zind || label_equirect) {
      const Image labels =
          zind ? LayoutLabels(*zind, view, options.layout) : RenderPanoLabelView(*label_equirect, view);
      WriteImageAtomic(out_dir / "labels" / name, labels);
      frame["labels"] = "labels/" + name;
      if (options.overlays) WriteImageAtomic(out_dir / "overlays" / name, DrawLabelOverlay(image, labels));
    }
    frames.push_back(std::move(frame));
    ReportProgress(
        progress,
        {.stage = "views", .done = static_cast<std::int64_t>(i + 1), .total = static_cast<std::int64_t>(views.size())});
  }

  nlohmann::json doc = {{"version", 1},
                        {"kind", "mono"},
                        {"camera",
                         {{"width", cam.width_px},
                          {"height", cam.height_px},
                          {"fx", cam.fx},
                          {"fy", cam.fy},
                          {"cx", cam.cx},
                          {"cy", cam.cy}}},
                        {"source",
                         {{"panorama", fs::absolute(panorama).lexically_normal().string()},
                          {"width", equirect.width()},
                          {"height", equirect.height()}}},
                        {"frames", std::move(frames)}};
  if (zind) {
    doc["source"]["zind"] = {{"pano", zind->Name()},
                             {"layout", ZindLayoutKindName(options.layout)},
                             {"label", zind->label},
                             {"metric", zind->metric},
                             {"ceiling_height_m", zind->ceiling_height_m}};
    doc["notice"] = kZindNotice;
    doc["truth"] = "truth.json";
    WritePlan(ZindTruthPlan(*zind, options.layout), out_dir / "truth.json");
  }
  PanoViewsSummary summary;
  summary.views = static_cast<int>(views.size());
  summary.labels = zind != nullptr || label_equirect.has_value();
  summary.truth = zind != nullptr;
  if (label_equirect) doc["source"]["labels"] = fs::absolute(options.label_panorama).lexically_normal().string();
  summary.views_json = out_dir / "capture.json";
  WriteFileAtomic(summary.views_json, doc.dump(1) + "\n");
  return summary;
}

}  // namespace asbuilt
