#ifndef ASBUILT_PANO_PANO_VIEWS_H_
#define ASBUILT_PANO_PANO_VIEWS_H_

// `asbuilt pano views`: a panorama turned into the perspective views a
// camera turning in place at its centre would take, written as a mono
// capture (capture.json, docs/formats.md, `asbuilt survey` reads it): the
// views, and for a ZInD panorama their layout labels, overlays and the
// room's truth plan.
//
//   OUT/capture.json         kind "mono": camera, and per view its image, yaw, pitch, position
//   OUT/images/NNN.png       the views (8-bit BGR)
//   OUT/labels/NNN.png       ZInD: layout labels (pano/layout_labels.h); or the
//                            nearest pixels of a label panorama (`label_panorama`)
//   OUT/overlays/NNN.png     with labels and `overlays`: labels over the view
//   OUT/truth.json           ZInD only: the room's plan (ZindTruthPlan), pano frame
//
// Everything is in the pano frame (formats/zind.h): the camera at
// (0, 0, camera height), yaw as DESIGN.md. Views derived from ZInD are for
// research measurement only (kZindNotice, which capture.json repeats).

#include <filesystem>
#include <optional>
#include <string>

#include "asbuilt/formats/zind.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct PanoViewsOptions {
  TurnInPlaceOptions turn;  // Size, focal length, view count, yaw step, pitch.
  // Camera height above the floor, metres, for each view's position_m; a
  // ZInD panorama's own height is used when this is unset.
  std::optional<double> camera_height_m;
  // A label panorama of the same scene (any 2:1 size): an 8-bit label PNG, or
  // the object-index EXR of `scene export-blender --panorama --labels-pass`.
  std::filesystem::path label_panorama;
  bool overlays = false;                         // With labels: also write overlays/NNN.png.
  ZindLayoutKind layout = ZindLayoutKind::kRaw;  // ZInD only: the layout the labels come from.
  void Check() const;
};

struct PanoViewsSummary {
  int views = 0;
  bool labels = false;               // labels/NNN.png written.
  bool truth = false;                // truth.json written (a ZInD panorama).
  std::filesystem::path views_json;  // The mono capture.json.
  std::string BriefReport()
      const;  // "12 views 640x480 (fx 400, yaw step 30°, pitch 0°) + layout labels → OUT/capture.json".
};

// Reads `panorama` (an equirectangular image) and writes its views into
// `out_dir` (created; existing files of the same names are replaced
// atomically). With `zind` (the panorama's annotation; its image is
// `panorama`) also labels, overlays and truth.json. Throws InputError when
// the image cannot be read or is not 2:1, InvalidArgument for bad options.
PanoViewsSummary WritePanoViews(const std::filesystem::path& panorama, const std::filesystem::path& out_dir,
                                const PanoViewsOptions& options, const ZindPanorama* zind = nullptr,
                                const ProgressCallback& progress = {});

// Reads an equirectangular panorama as 8-bit BGR. Throws InputError naming
// the file when it cannot be read or is not twice as wide as high.
Image ReadEquirect(const std::filesystem::path& path);

// Reads an equirectangular label panorama as 8-bit ids: a single-channel
// label PNG, or an OpenEXR whose first channel holds ids as floats (Blender's
// object-index pass). Throws InputError naming the file and the first pixel
// whose value is not a label id of DESIGN.md (0–3, 255), or when not 2:1.
Image ReadLabelEquirect(const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_PANO_PANO_VIEWS_H_
