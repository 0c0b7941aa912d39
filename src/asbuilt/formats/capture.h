#ifndef ASBUILT_FORMATS_CAPTURE_H_
#define ASBUILT_FORMATS_CAPTURE_H_

// capture.json — a stereo capture, the input of `asbuilt survey`
// (DESIGN.md "capture.json"). Image paths are stored as written (relative to
// the file's folder); Resolve() turns them into usable paths.

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

struct CaptureFrame {
  int index = 0;
  std::string left;    // Left image, relative to the capture's folder.
  std::string right;
  std::optional<std::string> labels;  // Synthetic only: left-view label ids.
  std::optional<std::string> depth;   // Synthetic only: left-view uint16 mm.
  double yaw_deg = 0.0;
  Vec3 position_m = Vec3(0, 0, 1.5);  // Rig centre, world metres.

  RigPose Pose() const { return {position_m, DegToRad(yaw_deg)}; }
};

struct Capture {
  int version = 1;
  CaptureCamera camera;
  bool rectified = true;
  std::optional<std::string> calibration;  // OpenCV YAML; needed if !rectified.
  std::vector<CaptureFrame> frames;

  // Folder the file was read from (not serialised); relative paths resolve
  // against it.
  std::filesystem::path base_dir;
  std::filesystem::path Resolve(const std::string& relative) const;

  std::string ToString() const;
};

// Reads and validates a capture. Throws InputError listing every problem with
// its field path: wrong types, NaN/inf, non-positive sizes or intrinsics, zero
// baseline, duplicate frame indices, missing image files, a missing
// calibration for an unrectified capture. Unknown keys are logged as warnings.
Capture ReadCapture(const std::filesystem::path& path);

// Same, from JSON already in memory: `name` stands for the file in messages,
// image paths resolve against `base_dir`.
Capture CaptureFromJson(const nlohmann::json& json, const std::string& name,
                        const std::filesystem::path& base_dir);

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
