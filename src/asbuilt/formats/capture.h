#ifndef ASBUILT_FORMATS_CAPTURE_H_
#define ASBUILT_FORMATS_CAPTURE_H_

// capture.json — the input of `asbuilt survey` (DESIGN.md "capture.json",
// docs/formats.md). Three kinds:
//   "stereo"    (the default when `kind` is absent) a stereo rig turned in
//               place: per frame a left and a right image;
//   "mono"      one level camera turned in place: per frame one `image`
//               (kept in CaptureFrame::left), no baseline;
//   "panorama"  one equirectangular 360° photo (2:1) taken at `position_m`
//               (the camera centre; its z is the height above the floor),
//               its left edge looking along world yaw `yaw_deg`.
// Mono and panorama captures place walls from their floor/ceiling label
// edges (docs/survey.md), so the camera height is required and must be > 0.
// Image paths are stored as written (relative to the file's folder);
// Resolve() turns them into usable paths.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/geometry/rig.h"
#include "asbuilt/util/error.h"

namespace asbuilt {

struct CaptureCamera {
  int width = 640;
  int height = 480;
  double fx = 400.0;
  double fy = 400.0;
  double cx = 319.5;
  double cy = 239.5;
  double baseline_m = 0.12;

  PinholeCamera Pinhole() const { return {width, height, fx, fy, cx, cy}; }
};

enum class CaptureKind { kStereo, kMono, kPanorama };
const char* CaptureKindName(CaptureKind kind);  // "stereo", "mono", "panorama".

struct CaptureFrame {
  int index = 0;
  std::string left;                   // Left image (a mono capture's only `image`), relative to the capture's folder.
  std::string right;                  // Empty in a mono capture.
  std::optional<std::string> labels;  // Synthetic only: left-view label ids.
  std::optional<std::string> depth;   // Synthetic only: left-view uint16 mm.
  double yaw_deg = 0.0;
  Vec3 position_m = Vec3(0, 0, 1.5);  // Rig centre (mono: camera centre), world metres.
  double pitch_deg = 0.0;             // Mono only: optical axis tilt, up positive (survey needs 0).

  RigPose Pose() const { return {position_m, DegToRad(yaw_deg)}; }
};

// A panorama capture's photo (CaptureKind::kPanorama).
struct CapturePanorama {
  std::string image;                  // Equirectangular, 2:1, relative to the capture's folder.
  Vec3 position_m = Vec3(0, 0, 1.5);  // Camera centre; z = height above the floor (> 0).
  double yaw_deg = 0.0;               // World yaw the image's left edge looks along.
};

struct Capture {
  int version = 1;
  CaptureKind kind = CaptureKind::kStereo;
  CaptureCamera camera;  // Stereo and mono (mono: baseline_m unused).
  bool rectified = true;
  std::optional<std::string> calibration;   // OpenCV YAML; needed if !rectified.
  std::vector<CaptureFrame> frames;         // Stereo and mono; empty for a panorama.
  std::optional<CapturePanorama> panorama;  // Panorama captures only.

  // Folder the file was read from (not serialised); relative paths resolve
  // against it.
  std::filesystem::path base_dir;
  std::filesystem::path Resolve(const std::string& relative) const;

  std::string ToString() const;
};

// Reads and validates a capture. Throws InputError listing every problem with
// its field path: wrong types, NaN/inf, non-positive sizes or intrinsics, zero
// baseline, duplicate frame indices, missing image files, a missing
// calibration for an unrectified capture; for mono and panorama captures a
// missing or non-positive camera height (position_m z), and a panorama
// whose PNG/JPEG header says it is not 2:1 (±1 px). Unknown keys are logged
// as warnings.
Capture ReadCapture(const std::filesystem::path& path);

// Same, from JSON already in memory: `name` stands for the file in messages,
// image paths resolve against `base_dir`.
Capture CaptureFromJson(const nlohmann::json& json, const std::string& name, const std::filesystem::path& base_dir);

// Every problem in a capture file (errors and warnings), without throwing.
struct FileReport {
  std::vector<Problem> errors;
  std::vector<Problem> warnings;
};
FileReport CheckCaptureFile(const std::filesystem::path& path);

// Writes atomically; paths are written as stored.
void WriteCapture(const Capture& capture, const std::filesystem::path& path);
nlohmann::json CaptureToJson(const Capture& capture);

}  // namespace asbuilt

#endif  // ASBUILT_FORMATS_CAPTURE_H_
