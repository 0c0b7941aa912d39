#ifndef ASBUILT_PIPELINE_ZIND_EVAL_H_
#define ASBUILT_PIPELINE_ZIND_EVAL_H_

// `asbuilt eval zind`: the segmenter on real photographs (issue 21). Each
// benchmark panorama of a ZInD tour (primary, taken inside its room) is
// turned into perspective views (pano/perspective.h: by default 12 views,
// 640×480, fx = fy = 400, yaw step 30°, pitch 0), labelled from its
// annotated layout (pano/layout_labels.h), segmented, and scored with
// mmseg's metrics (seg/metrics.h) over
//   - whole views, and
//   - the upper half: pixels whose ray points above the horizon (the rows
//     above cy at pitch 0), where furniture rarely stands in front of the
//     walls. Layout labels call furniture in front of a wall "wall", so the
//     lower half measures the layout more than the segmenter.
// ZInD passages (openings) are ignored (255).
//
// LICENCE: ZInD is for academic use only. It is a test set, never training
// data; nothing derived from it is committed or shipped. Every output says
// so (kZindNotice).
//
// Outputs in `out_dir` (when not empty): metrics.json, metrics.md,
// report.html (per panorama: figures and a contact sheet), sheets/<pano>.jpg
// (each view's layout labels over the photo, above the segmenter's).

#include <filesystem>
#include <stop_token>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "asbuilt/formats/zind.h"
#include "asbuilt/pano/perspective.h"
#include "asbuilt/seg/metrics.h"
#include "asbuilt/seg/segmenter.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

struct ZindEvalOptions {
  TurnInPlaceOptions turn;                       // The views of each panorama (issue 21: the defaults).
  ZindLayoutKind layout = ZindLayoutKind::kRaw;  // The layout the labels come from.
  int max_panoramas = 0;                         // Score at most N benchmark panoramas (0 = all), for quick checks.
  int batch_size = 4;                            // Views per forward pass.
  bool write_sheets = true;                      // Contact sheets and report.html (when out_dir is given).
  // How reports name the segmenter (its file, the scale it ran at); empty:
  // the checkpoint's own description (SegmenterInfo::ToString()).
  std::string segmenter_name;
  void Check() const;
};

// One panorama's figures.
struct ZindPanoramaScore {
  std::string name;   // ZindPanorama::Name().
  std::string label;  // "bedroom".
  int views = 0;
  SegmentationMetrics whole, upper;
  std::string sheet;  // Contact sheet, relative to out_dir; empty when none.
};

struct ZindEvalSummary {
  std::string tour;   // The tour folder.
  std::string model;  // ZindEvalOptions::segmenter_name, else SegmenterInfo::ToString().
  std::string views;  // "12 views 640x480, fx 400, yaw step 30°, pitch 0°, layout_raw".
  int panoramas = 0, images = 0;
  SegmentationMetrics whole, upper;  // Pooled over every view.
  std::vector<ZindPanoramaScore> per_panorama;
  double seconds = 0;
  std::filesystem::path out_dir;  // Empty when nothing was written.

  // "ZInD 13 panoramas, 156 views: mIoU 0.234 (wall 0.499 door 0.075 window 0.194); upper half mIoU …".
  std::string BriefReport() const;
  // Notice, set-up, whole and upper-half tables (IoU, precision, recall per
  // class), per-panorama mIoU; Markdown.
  std::string ToMarkdown() const;
  nlohmann::json ToJson() const;
};

// Scores `segmenter` on the tour's benchmark panoramas. Throws InputError
// naming a panorama image that cannot be read; InvalidArgument for bad
// options or a tour without benchmark panoramas.
ZindEvalSummary EvaluateOnZind(Segmenter& segmenter, const ZindTour& tour, const std::filesystem::path& out_dir,
                               const ZindEvalOptions& options = {}, const ProgressCallback& progress = {},
                               std::stop_token stop = {});

}  // namespace asbuilt

#endif  // ASBUILT_PIPELINE_ZIND_EVAL_H_
