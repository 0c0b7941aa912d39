#include "asbuilt/formats/capture.h"

#include <set>

#include <fmt/format.h>

#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

// Intrinsics beyond these are surely a mistake (e.g. mm given for pixels).
constexpr int kMaxImageSidePx = 32768;

Capture ParseCaptureJson(const nlohmann::json& root, const fs::path& base_dir,
                         JsonDiagnostics& diag) {
  Capture capture;
  capture.base_dir = base_dir;
  JsonField doc(root, diag);
  if (!doc.Object({"version", "camera", "rectified", "calibration", "frames"})) {
    return capture;
  }
  if (auto v = doc.Required("version").Integer()) {
    if (*v != 1) doc.Required("version").AddError(fmt::format("unsupported version {}, expected 1", *v));
  }

  JsonField cam = doc.Required("camera");
  if (cam.Object({"width", "height", "fx", "fy", "cx", "cy", "baseline_m"})) {
    auto read_size = [&](const char* key, int& out) {
      JsonField f = cam.Required(key);
      if (auto v = f.Integer()) {
        if (*v <= 0 || *v > kMaxImageSidePx) {
          f.AddError(fmt::format("must be in 1..{}, got {}", kMaxImageSidePx, *v));
        } else {
          out = static_cast<int>(*v);
        }
      }
    };
    read_size("width", capture.camera.width);
    read_size("height", capture.camera.height);
    for (auto [key, out] : {std::pair{"fx", &capture.camera.fx}, std::pair{"fy", &capture.camera.fy}}) {
      JsonField f = cam.Required(key);
      if (auto v = f.Positive()) {
        if (*v > 100.0 * kMaxImageSidePx) {
          f.AddError(fmt::format("focal length {} px is absurd", *v));
        } else {
          *out = *v;
        }
      }
    }
    if (auto v = cam.Required("cx").Number()) capture.camera.cx = *v;
    if (auto v = cam.Required("cy").Number()) capture.camera.cy = *v;
    JsonField baseline = cam.Required("baseline_m");
    if (auto v = baseline.Number()) {
      if (*v == 0) {
        baseline.AddError("baseline is zero: a stereo rig needs two separated cameras");
      } else if (*v < 0) {
        baseline.AddError(fmt::format("must be > 0, got {}", *v));
      } else if (*v > 10) {
        baseline.AddError(fmt::format("baseline {} m is absurd (metres expected)", *v));
      } else {
        capture.camera.baseline_m = *v;
      }
    }
    // The principal point should lie inside the image.
    if (diag.ok() && (capture.camera.cx < -0.5 || capture.camera.cx > capture.camera.width - 0.5)) {
      cam.Required("cx").AddError(fmt::format("principal point x {} lies outside the image width {}",
                                              capture.camera.cx, capture.camera.width));
    }
    if (diag.ok() && (capture.camera.cy < -0.5 || capture.camera.cy > capture.camera.height - 0.5)) {
      cam.Required("cy").AddError(fmt::format("principal point y {} lies outside the image height {}",
                                              capture.camera.cy, capture.camera.height));
    }
  }

  if (auto v = doc.Optional("rectified").Bool()) capture.rectified = *v;
  if (auto v = doc.Optional("calibration").String()) {
    capture.calibration = *v;
    if (!fs::exists(capture.Resolve(*v))) {
      doc.Optional("calibration").AddError(fmt::format("file not found: {}", capture.Resolve(*v).string()));
    }
  }
  if (!capture.rectified && !capture.calibration) {
    doc.Optional("calibration").AddError(
        "required when rectified is false (an OpenCV YAML from `asbuilt calibrate`)");
  }

  JsonField frames = doc.Required("frames");
  std::optional<std::size_t> n = frames.ArraySize(1);
  std::set<std::int64_t> seen;
  for (std::size_t i = 0; n && i < *n; ++i) {
    JsonField fr = frames.At(i);
    CaptureFrame frame;
    if (!fr.Object({"index", "left", "right", "labels", "depth", "yaw_deg", "position_m"})) continue;
    if (auto v = fr.Required("index").Integer()) {
      if (*v < 0) {
        fr.Required("index").AddError(fmt::format("must be >= 0, got {}", *v));
      } else if (!seen.insert(*v).second) {
        fr.Required("index").AddError(fmt::format("duplicate frame index {}", *v));
      } else {
        frame.index = static_cast<int>(*v);
      }
    }
    auto read_image = [&](const char* key, bool required) -> std::optional<std::string> {
      JsonField f = required ? fr.Required(key) : fr.Optional(key);
      auto v = f.String();
      if (!v) return std::nullopt;
      if (v->empty()) {
        f.AddError("empty path");
        return std::nullopt;
      }
      fs::path resolved = capture.Resolve(*v);
      std::error_code ec;
      if (!fs::is_regular_file(resolved, ec)) {
        f.AddError(fmt::format("image not found: {}", resolved.string()));
      }
      return v;
    };
    if (auto v = read_image("left", true)) frame.left = *v;
    if (auto v = read_image("right", true)) frame.right = *v;
    frame.labels = read_image("labels", false);
    frame.depth = read_image("depth", false);
    if (auto v = fr.Required("yaw_deg").Number()) frame.yaw_deg = *v;
    if (auto v = fr.Required("position_m").NumberArray(3)) {
      frame.position_m = Vec3((*v)[0], (*v)[1], (*v)[2]);
    }
    capture.frames.push_back(std::move(frame));
  }
  return capture;
}

Capture ParseCapture(const fs::path& path, JsonDiagnostics& diag) {
  nlohmann::json root = ParseJsonFile(path, diag);
  if (!diag.ok()) {
    Capture capture;
    capture.base_dir = path.parent_path();
    return capture;
  }
  return ParseCaptureJson(root, path.parent_path(), diag);
}

}  // namespace

Capture CaptureFromJson(const nlohmann::json& json, const std::string& name,
                        const fs::path& base_dir) {
  JsonDiagnostics diag(name);
  Capture capture = ParseCaptureJson(json, base_dir, diag);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return capture;
}

fs::path Capture::Resolve(const std::string& relative) const {
  fs::path p(relative);
  return p.is_absolute() ? p : base_dir / p;
}

std::string Capture::ToString() const {
  return fmt::format("Capture({} frames, {}x{}, baseline {:.3f} m, {})", frames.size(),
                     camera.width, camera.height, camera.baseline_m,
                     rectified ? "rectified" : "unrectified");
}

Capture ReadCapture(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  Capture capture = ParseCapture(path, diag);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return capture;
}

FileReport CheckCaptureFile(const fs::path& path) {
  JsonDiagnostics diag(path.string());
  ParseCapture(path, diag);
  return {diag.errors(), diag.warnings()};
}

nlohmann::json CaptureToJson(const Capture& capture) {
  nlohmann::json j;
  j["version"] = capture.version;
  j["camera"] = {{"width", capture.camera.width},   {"height", capture.camera.height},
                 {"fx", capture.camera.fx},         {"fy", capture.camera.fy},
                 {"cx", capture.camera.cx},         {"cy", capture.camera.cy},
                 {"baseline_m", capture.camera.baseline_m}};
  j["rectified"] = capture.rectified;
  if (capture.calibration) j["calibration"] = *capture.calibration;
  nlohmann::json frames = nlohmann::json::array();
  for (const CaptureFrame& f : capture.frames) {
    nlohmann::json jf = {{"index", f.index}, {"left", f.left}, {"right", f.right}};
    if (f.labels) jf["labels"] = *f.labels;
    if (f.depth) jf["depth"] = *f.depth;
    jf["yaw_deg"] = f.yaw_deg;
    jf["position_m"] = {f.position_m.x(), f.position_m.y(), f.position_m.z()};
    frames.push_back(std::move(jf));
  }
  j["frames"] = std::move(frames);
  return j;
}

void WriteCapture(const Capture& capture, const fs::path& path) {
  WriteFileAtomic(path, CaptureToJson(capture).dump(2) + "\n");
}

}  // namespace asbuilt
