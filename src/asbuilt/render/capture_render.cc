#include "asbuilt/render/capture_render.h"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/plan_file.h"
#include "asbuilt/imageio/image_io.h"
#include "asbuilt/util/error.h"

namespace asbuilt {
namespace fs = std::filesystem;

void CaptureRenderOptions::Check() const {
  render.Check();
  CheckArgument(views >= 0 && views <= 3600,
                fmt::format("CaptureRenderOptions.views = {}, must be in [0, 3600]", views));
  CheckArgument(std::isfinite(step_deg) && step_deg >= 0 && step_deg <= 360,
                fmt::format("CaptureRenderOptions.step_deg = {}, must be in [0, 360]", step_deg));
  CheckArgument(
      width_px >= 0 && width_px <= 16384 && height_px >= 0 && height_px <= 16384 && (width_px == 0) == (height_px == 0),
      fmt::format("CaptureRenderOptions size = {}x{}, must be both 0 or both in [1, 16384]", width_px, height_px));
  CheckArgument(std::isfinite(fov_deg) && fov_deg >= 0 && fov_deg < 179,
                fmt::format("CaptureRenderOptions.fov_deg = {}, must be 0 or in (0, 179)", fov_deg));
  CheckArgument(std::isfinite(baseline_m) && baseline_m >= 0 && baseline_m <= 10,
                fmt::format("CaptureRenderOptions.baseline_m = {}, must be 0 or in (0, 10]", baseline_m));
}

std::string CaptureRenderSummary::BriefReport() const {
  return fmt::format("rendered {} of {} views ({} already done) in {:.1f} s → {}", rendered, views, skipped, seconds,
                     out_dir);
}

CaptureViews ResolveCaptureViews(const Scene& scene, const CaptureRenderOptions& options) {
  options.Check();
  CaptureViews v;
  StereoRigSpec rig = scene.rig;
  if (options.width_px > 0) {
    // A new size keeps the field of view unless intrinsics were explicit.
    if (rig.fx && options.fov_deg == 0) rig.hfov_deg = RadToDeg(2 * std::atan(0.5 * rig.width_px / *rig.fx));
    rig.fx.reset();
    rig.fy.reset();
    rig.cx.reset();
    rig.cy.reset();
    rig.width_px = options.width_px;
    rig.height_px = options.height_px;
  }
  if (options.fov_deg > 0) {
    rig.fx.reset();
    rig.fy.reset();
    rig.cx.reset();
    rig.cy.reset();
    rig.hfov_deg = options.fov_deg;
  }
  v.camera = rig.Camera();
  v.baseline_m = options.baseline_m > 0 ? options.baseline_m : rig.baseline_m;

  if (options.views > 0 || options.step_deg > 0) {
    Vec3 position(0, 0, 1.5);
    double start = 0.0;
    if (scene.turn) {
      position = scene.turn->position_m;
      start = scene.turn->start_deg;
    } else if (!scene.viewpoints.empty()) {
      position = scene.viewpoints.front().position_m;
      start = scene.viewpoints.front().yaw_deg;
    } else if (!scene.rooms.empty() && !scene.rooms[0].polygon.empty()) {
      Vec2 c = Vec2::Zero();
      for (const Vec2& p : scene.rooms[0].polygon) c += p;
      c /= static_cast<double>(scene.rooms[0].polygon.size());
      position = Vec3(c.x(), c.y(), 1.5);
    }
    double step = options.step_deg > 0 ? options.step_deg : 360.0 / options.views;
    int count = options.views > 0 ? options.views : std::max(1, static_cast<int>(std::floor(360.0 / step + 1e-9)));
    for (int i = 0; i < count; ++i) v.viewpoints.push_back({position, start + i * step, 0.0});
  } else {
    v.viewpoints = ResolveViewpoints(scene);
  }
  return v;
}

CaptureRenderSummary RenderCapture(const Scene& scene, const fs::path& out_dir, const CaptureRenderOptions& options,
                                   const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  CaptureViews views = ResolveCaptureViews(scene, options);
  if (views.viewpoints.empty()) {
    throw InputError("scene", "viewpoints", "no views to render (give viewpoints, a turn, or --views)");
  }
  for (std::size_t i = 0; i < views.viewpoints.size(); ++i) {
    if (std::abs(views.viewpoints[i].pitch_deg) > 1e-9) {
      throw InputError("scene", fmt::format("viewpoints[{}].pitch_deg", i),
                       "a capture's rig is level; pitched views belong in `asbuilt dataset synth`");
    }
  }
  CaptureRenderSummary summary;
  summary.views = static_cast<int>(views.viewpoints.size());
  summary.out_dir = out_dir.string();

  Capture capture;
  capture.camera = {views.camera.width_px, views.camera.height_px, views.camera.fx, views.camera.fy,
                    views.camera.cx,       views.camera.cy,        views.baseline_m};
  capture.rectified = true;
  std::unique_ptr<SceneRenderer> renderer;
  const int digits = views.viewpoints.size() > 1000 ? 4 : 3;
  for (std::size_t i = 0; i < views.viewpoints.size(); ++i) {
    const Viewpoint& vp = views.viewpoints[i];
    const std::string name = fmt::format("{:0{}d}.png", i, digits);
    CaptureFrame frame;
    frame.index = static_cast<int>(i);
    frame.left = "left/" + name;
    frame.right = "right/" + name;
    frame.labels = "labels/" + name;
    frame.depth = "depth/" + name;
    frame.yaw_deg = vp.yaw_deg;
    frame.position_m = vp.position_m;
    capture.frames.push_back(frame);

    std::vector<std::string> files = {frame.left, frame.right, *frame.labels, *frame.depth, "idmap/" + name};
    if (options.render.normals) files.push_back("normals/" + name);
    if (options.render.instance_ids) files.push_back("instances/" + name);
    bool done = options.resume;
    for (const std::string& f : files) done = done && fs::exists(out_dir / f);
    if (done) {
      ++summary.skipped;
    } else {
      if (!renderer) renderer = std::make_unique<SceneRenderer>(scene);
      RenderedView view = renderer->Render({views.camera, vp, views.baseline_m}, options.render, i);
      WriteImageAtomic(out_dir / frame.left, view.left);
      WriteImageAtomic(out_dir / frame.right, view.right);
      WriteImageAtomic(out_dir / *frame.labels, view.labels);
      WriteImageAtomic(out_dir / *frame.depth, view.depth_mm);
      WriteImageAtomic(out_dir / "idmap" / name, view.idmap);
      if (options.render.normals) WriteImageAtomic(out_dir / "normals" / name, view.normals);
      if (options.render.instance_ids) WriteImageAtomic(out_dir / "instances" / name, view.instance_ids);
      ++summary.rendered;
    }
    ReportProgress(
        progress, {"render", static_cast<std::int64_t>(i + 1), static_cast<std::int64_t>(views.viewpoints.size()), ""});
  }
  WritePlan(SceneTruth(scene), out_dir / "truth.json");
  WriteCapture(capture, out_dir / "capture.json");
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace asbuilt
