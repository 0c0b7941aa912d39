#ifndef ASBUILT_BENCH_ZIND_CAPTURE_H_
#define ASBUILT_BENCH_ZIND_CAPTURE_H_

// A ZInD panorama as the capture a user would write for it (capture.json in
// `dir`): the photo where it lies, the camera at its annotated height, in
// the pano frame. Shared by the benches that survey ZInD (read at run time,
// research measurement only; nothing derived from it is committed).

#include <filesystem>

#include <nlohmann/json.hpp>

#include "asbuilt/formats/zind.h"
#include "asbuilt/util/file.h"

namespace asbuilt::bench {

inline std::filesystem::path WriteZindCapture(const ZindPanorama& pano, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const nlohmann::json capture = {{"version", 1},
                                  {"kind", "panorama"},
                                  {"panorama", std::filesystem::absolute(pano.image).lexically_normal().string()},
                                  {"position_m", {0.0, 0.0, pano.camera_height_m}},
                                  {"yaw_deg", 0.0}};
  WriteFileAtomic(dir / "capture.json", capture.dump(2) + "\n");
  return dir / "capture.json";
}

}  // namespace asbuilt::bench

#endif  // ASBUILT_BENCH_ZIND_CAPTURE_H_
