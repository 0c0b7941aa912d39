#include "asbuilt/formats/capture.h"

#include <fstream>
#include <set>

#include <fmt/format.h>

#include "asbuilt/util/file.h"
#include "asbuilt/util/json_reader.h"

namespace asbuilt {
namespace fs = std::filesystem;
namespace {

// Intrinsics beyond these are surely a mistake (e.g. mm given for pixels).
constexpr int kMaxImageSidePx = 32768;

// Width and height from a PNG or baseline/progressive JPEG header, so the
// reader can check a panorama's shape without decoding it (formats/ has no
// OpenCV); nullopt for other formats or a header it cannot read.
std::optional<std::pair<int, int>> ImageSizeFromHeader(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  unsigned char head[24] = {};
  in.read(reinterpret_cast<char*>(head), sizeof head);
  if (in.gcount() < 4) return std::nullopt;
  auto be16 = [](const unsigned char* p) { return (p[0] << 8) | p[1]; };
  auto be32 = [](const unsigned char* p) {
    return static_cast<std::int64_t>(p[0]) << 24 | p[1] << 16 | p[2] << 8 | p[3];
  };
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (in.gcount() == 24 && std::equal(kPng, kPng + 8, head) && std::equal(head + 12, head + 16, "IHDR")) {
    return std::pair(static_cast<int>(be32(head + 16)), static_cast<int>(be32(head + 20)));
  }
  if (head[0] != 0xFF || head[1] != 0xD8) return std::nullopt;
  // JPEG: walk the marker segments to the first start-of-frame.
  in.clear();
  in.seekg(2);
  for (int guard = 0; guard < 10000; ++guard) {
    unsigned char m[4];
    if (!in.read(reinterpret_cast<char*>(m), 2) || m[0] != 0xFF) return std::nullopt;
    while (m[1] == 0xFF) {
      if (!in.read(reinterpret_cast<char*>(m + 1), 1)) return std::nullopt;
    }
    const int marker = m[1];
    if (marker == 0xD8 || (marker >= 0xD0 && marker <= 0xD7) || marker == 0x01) continue;
    if (!in.read(reinterpret_cast<char*>(m + 2), 2)) return std::nullopt;
    const int length = be16(m + 2);
    if (length < 2) return std::nullopt;
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      unsigned char f[5];
      if (!in.read(reinterpret_cast<char*>(f), 5)) return std::nullopt;
      return std::pair(be16(f + 3), be16(f + 1));
    }
    in.seekg(length - 2, std::ios::cur);
  }
  return std::nullopt;
}

CaptureKind ParseKind(const std::string& name, bool* ok) {
  for (CaptureKind k : {CaptureKind::kStereo, CaptureKind::kMono, CaptureKind::kPanorama}) {
    if (name == CaptureKindName(k)) return k;
  }
  *ok = false;
  return CaptureKind::kStereo;
}

// The camera's height above the floor (position_m z) must be positive:
// mono and panorama surveys place walls from it.
void RequireCameraHeight(const JsonField& field, const Vec3& position_m) {
  if (!(position_m.z() > 0)) {
    field.AddError(fmt::format("the camera's height above the floor (z) must be > 0, got {}: walls are placed from it",
                               position_m.z()));
  }
}

Capture ParseCaptureJson(const nlohmann::json& root, const fs::path& base_dir, JsonDiagnostics& diag) {
  Capture capture;
  capture.base_dir = base_dir;
  JsonField doc(root, diag);
  if (root.is_object() && root.contains("kind") && root["kind"].is_string()) {
    bool ok = true;
    capture.kind = ParseKind(root["kind"].get<std::string>(), &ok);
    if (!ok) {
      doc.Required("kind").AddError(
          fmt::format("unknown kind \"{}\", expected stereo, mono or panorama", root["kind"].get<std::string>()));
      return capture;
    }
  } else if (root.is_object() && root.contains("kind")) {
    doc.Required("kind").String();  // Reports the type error.
    return capture;
  }
  const bool stereo = capture.kind == CaptureKind::kStereo;
  const bool known = capture.kind == CaptureKind::kPanorama
                         ? doc.Object({"version", "kind", "panorama", "position_m", "yaw_deg"})
                     : stereo ? doc.Object({"version", "kind", "camera", "rectified", "calibration", "frames"})
                              // `asbuilt pano views` says where its views came from.
                              : doc.Object({"version", "kind", "camera", "rectified", "calibration", "frames", "source",
                                            "notice", "truth"});
  if (!known) return capture;
  if (auto v = doc.Required("version").Integer()) {
    if (*v != 1) doc.Required("version").AddError(fmt::format("unsupported version {}, expected 1", *v));
  }
  if (capture.kind == CaptureKind::kPanorama) {
    CapturePanorama pano;
    JsonField image = doc.Required("panorama");
    if (auto v = image.String()) {
      pano.image = *v;
      std::error_code ec;
      const fs::path resolved = capture.Resolve(*v);
      if (v->empty()) {
        image.AddError("empty path");
      } else if (!fs::is_regular_file(resolved, ec)) {
        image.AddError(fmt::format("image not found: {}", resolved.string()));
      } else if (auto size = ImageSizeFromHeader(resolved); size && std::abs(size->first - 2 * size->second) > 1) {
        image.AddError(fmt::format("{} is {}x{}: an equirectangular panorama is twice as wide as high",
                                   resolved.string(), size->first, size->second));
      }
    }
    JsonField position = doc.Required("position_m");
    if (auto v = position.NumberArray(3)) {
      pano.position_m = Vec3((*v)[0], (*v)[1], (*v)[2]);
      RequireCameraHeight(position, pano.position_m);
    }
    if (auto v = doc.Optional("yaw_deg").Number()) pano.yaw_deg = *v;
    capture.panorama = std::move(pano);
    return capture;
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
    JsonField baseline = stereo ? cam.Required("baseline_m") : cam.Optional("baseline_m");
    if (!stereo) {
      if (baseline.present()) baseline.AddWarning("ignored: a mono capture has one camera");
    } else if (auto v = baseline.Number()) {
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
      cam.Required("cx").AddError(
          fmt::format("principal point x {} lies outside the image width {}", capture.camera.cx, capture.camera.width));
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
  if (!stereo && !capture.rectified) {
    doc.Optional("rectified").AddError("a mono capture's views must be undistorted pinhole images (rectified: true)");
  } else if (!capture.rectified && !capture.calibration) {
    doc.Optional("calibration").AddError("required when rectified is false (an OpenCV YAML from `asbuilt calibrate`)");
  }

  JsonField frames = doc.Required("frames");
  std::optional<std::size_t> n = frames.ArraySize(1);
  std::set<std::int64_t> seen;
  for (std::size_t i = 0; n && i < *n; ++i) {
    JsonField fr = frames.At(i);
    CaptureFrame frame;
    const bool frame_ok = stereo ? fr.Object({"index", "left", "right", "labels", "depth", "yaw_deg", "position_m"})
                                 : fr.Object({"index", "image", "labels", "yaw_deg", "pitch_deg", "position_m"});
    if (!frame_ok) continue;
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
    if (stereo) {
      if (auto v = read_image("left", true)) frame.left = *v;
      if (auto v = read_image("right", true)) frame.right = *v;
      frame.depth = read_image("depth", false);
    } else if (auto v = read_image("image", true)) {
      frame.left = *v;
    }
    frame.labels = read_image("labels", false);
    if (auto v = fr.Required("yaw_deg").Number()) frame.yaw_deg = *v;
    if (!stereo) {
      if (auto v = fr.Optional("pitch_deg").Number()) frame.pitch_deg = *v;
    }
    if (auto v = fr.Required("position_m").NumberArray(3)) {
      frame.position_m = Vec3((*v)[0], (*v)[1], (*v)[2]);
      if (!stereo) RequireCameraHeight(fr.Required("position_m"), frame.position_m);
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

Capture CaptureFromJson(const nlohmann::json& json, const std::string& name, const fs::path& base_dir) {
  JsonDiagnostics diag(name);
  Capture capture = ParseCaptureJson(json, base_dir, diag);
  diag.ThrowIfErrors();
  diag.LogWarnings();
  return capture;
}

const char* CaptureKindName(CaptureKind kind) {
  switch (kind) {
    case CaptureKind::kStereo:
      return "stereo";
    case CaptureKind::kMono:
      return "mono";
    case CaptureKind::kPanorama:
      return "panorama";
  }
  return "?";
}

fs::path Capture::Resolve(const std::string& relative) const {
  fs::path p(relative);
  return p.is_absolute() ? p : base_dir / p;
}

std::string Capture::ToString() const {
  if (kind == CaptureKind::kPanorama && panorama) {
    return fmt::format("Capture(panorama {}, camera at ({:.3f}, {:.3f}, {:.3f}) m, yaw {:.1f}°)", panorama->image,
                       panorama->position_m.x(), panorama->position_m.y(), panorama->position_m.z(), panorama->yaw_deg);
  }
  if (kind == CaptureKind::kMono) {
    return fmt::format("Capture(mono, {} frames, {}x{})", frames.size(), camera.width, camera.height);
  }
  return fmt::format("Capture({} frames, {}x{}, baseline {:.3f} m, {})", frames.size(), camera.width, camera.height,
                     camera.baseline_m, rectified ? "rectified" : "unrectified");
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
  if (capture.kind == CaptureKind::kPanorama) {
    const CapturePanorama pano = capture.panorama.value_or(CapturePanorama{});
    j["kind"] = "panorama";
    j["panorama"] = pano.image;
    j["position_m"] = {pano.position_m.x(), pano.position_m.y(), pano.position_m.z()};
    j["yaw_deg"] = pano.yaw_deg;
    return j;
  }
  const bool stereo = capture.kind == CaptureKind::kStereo;
  if (!stereo) j["kind"] = CaptureKindName(capture.kind);
  j["camera"] = {{"width", capture.camera.width}, {"height", capture.camera.height}, {"fx", capture.camera.fx},
                 {"fy", capture.camera.fy},       {"cx", capture.camera.cx},         {"cy", capture.camera.cy}};
  if (stereo) {
    j["camera"]["baseline_m"] = capture.camera.baseline_m;
    j["rectified"] = capture.rectified;
    if (capture.calibration) j["calibration"] = *capture.calibration;
  }
  nlohmann::json frames = nlohmann::json::array();
  for (const CaptureFrame& f : capture.frames) {
    nlohmann::json jf = {{"index", f.index}};
    if (stereo) {
      jf["left"] = f.left;
      jf["right"] = f.right;
    } else {
      jf["image"] = f.left;
    }
    if (f.labels) jf["labels"] = *f.labels;
    if (f.depth) jf["depth"] = *f.depth;
    jf["yaw_deg"] = f.yaw_deg;
    if (!stereo && f.pitch_deg != 0) jf["pitch_deg"] = f.pitch_deg;
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
