#include "asbuilt/pano/pano_views.h"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "asbuilt/formats/plan_file.h"
#include "asbuilt/imageio/image_cv.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/pano/layout_labels.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

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
  return fmt::format("{} view{}{} → {}", views, views == 1 ? "" : "s", labels ? " + layout labels + truth.json" : "",
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

PanoViewsSummary WritePanoViews(const fs::path& panorama, const fs::path& out_dir, const PanoViewsOptions& options,
                                const ZindPanorama* zind, const ProgressCallback& progress) {
  options.Check();
  const std::vector<PanoView> views = TurnInPlaceViews(options.turn);
  const Image equirect = ReadEquirect(panorama);
  std::optional<double> height = options.camera_height_m;
  if (!height && zind) height = zind->camera_height_m;
  if (zind) zind->Layout(options.layout);  // Throws now if the layout is missing.

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
    if (zind) {
      const Image labels = LayoutLabels(*zind, view, options.layout);
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
  summary.labels = zind != nullptr;
  summary.views_json = out_dir / "capture.json";
  WriteFileAtomic(summary.views_json, doc.dump(1) + "\n");
  return summary;
}

}  // namespace asbuilt
