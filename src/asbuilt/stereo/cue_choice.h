#ifndef ASBUILT_STEREO_CUE_CHOICE_H_
#define ASBUILT_STEREO_CUE_CHOICE_H_

// The wall cue of a capture (FramePointsOptions::contacts): stereo, or the
// floor/ceiling contacts where the walls' stereo fails the column check. A
// level camera sees a vertical wall at one depth down each image column, so
// a wall's disparities down a column should agree with their median; on
// plain paint they scatter (docs/stereo.md "Which cue places the walls").

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/stereo/contacts.h"
#include "asbuilt/stereo/disparity.h"
#include "asbuilt/stereo/frame_points.h"
#include "asbuilt/stereo/frame_points_options.h"

namespace asbuilt {

// The column check of one frame's wall stereo.
struct WallStereoCheck {
  int checked = 0;  // Wall pixels of columns with at least 20 valid ones.
  int agreed = 0;   // Those within max(stereo_check_tolerance_px, 3 %) of their
                    // column's median.
};
// Every contact_col_step_px-th column of `labels` (CV_8UC1) against
// `disparity`.
WallStereoCheck CheckWallStereo(const cv::Mat& labels, const DisparityResult& disparity,
                                const FramePointsOptions& options);

// Gathers a capture's frames and, with ContactUse::kWhereStereoFails, picks
// the wall cue for the whole capture (a room's walls share their paint): the
// contact alternative when the frames' wall stereo, pooled, fails the column
// check (FramePointsOptions::stereo_check_*) and there are contacts to
// replace it; the stereo alternative otherwise.
class CapturePoints {
 public:
  explicit CapturePoints(const FramePointsOptions& options) : options_(options) {}
  // Takes the frame's points, contacts and cues (the rest of `r` is left).
  void Add(FramePointsResult& r);

  struct Result {
    std::vector<ClassPoint> points;
    bool contacts_used = false;     // Contact points are among `points`.
    std::string decision;           // Why, in a sentence (empty with kOff).
    std::vector<FrameCues> frames;  // Each frame's cues, of the alternative chosen.
    int stereo_checked = 0, stereo_agreed = 0;
    ResolvedContacts contacts;  // Ceiling height and its provenance (points moved out).
  };
  Result Finish();

 private:
  FramePointsOptions options_;
  std::vector<ClassPoint> stereo_points_, contact_points_;
  std::vector<FrameCues> stereo_cues_, contact_cues_;
  PendingContacts pending_;
  int stereo_checked_ = 0, stereo_agreed_ = 0;
};

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_CUE_CHOICE_H_
