#include "asbuilt/stereo/cue_choice.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "asbuilt/geometry/label_class.h"
#include "asbuilt/util/error.h"

namespace asbuilt {

// The measured agreement of textured and plain walls: docs/stereo.md
// "Which cue places the walls".
WallStereoCheck CheckWallStereo(const cv::Mat& labels, const DisparityResult& disparity,
                                const FramePointsOptions& options) {
  constexpr int kMinRun = 20;
  WallStereoCheck check;
  std::vector<float> column;
  for (int u = 0; u < labels.cols; u += options.contact_col_step_px) {
    column.clear();
    for (int v = 0; v < labels.rows; ++v) {
      const float d = disparity.disparity_px.at<float>(v, u);
      if (labels.at<unsigned char>(v, u) == 1 && disparity.valid.at<unsigned char>(v, u) && std::isfinite(d)) {
        column.push_back(d);
      }
    }
    if (column.size() < kMinRun) continue;
    std::vector<float> sorted = column;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    const double tolerance = std::max(options.stereo_check_tolerance_px, 0.03 * median);
    check.checked += static_cast<int>(column.size());
    for (float d : column) check.agreed += std::abs(d - median) <= tolerance;
  }
  return check;
}

const char* ContactUseName(ContactUse use) {
  switch (use) {
    case ContactUse::kOff:
      return "off";
    case ContactUse::kWhereStereoFails:
      return "auto";
    case ContactUse::kAlways:
      return "always";
  }
  return "?";
}

ContactUse ParseContactUse(const std::string& name) {
  for (ContactUse use : {ContactUse::kOff, ContactUse::kWhereStereoFails, ContactUse::kAlways}) {
    if (name == ContactUseName(use)) return use;
  }
  throw InvalidArgument(fmt::format("contacts = \"{}\": must be off, auto or always", name));
}

void CapturePoints::Add(FramePointsResult& r) {
  auto take = [](std::vector<ClassPoint>& from, std::vector<ClassPoint>& to) {
    to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
    from.clear();
  };
  take(r.points, stereo_points_);
  take(r.contact_points, contact_points_);
  pending_.Append(std::move(r.contacts));
  stereo_checked_ += r.cues.stereo_checked;
  stereo_agreed_ += r.cues.stereo_agreed;
  stereo_cues_.push_back(r.cues);
  contact_cues_.push_back(r.contact_cues);
}

CapturePoints::Result CapturePoints::Finish() {
  Result out{.stereo_checked = stereo_checked_, .stereo_agreed = stereo_agreed_};
  switch (options_.contacts) {
    case ContactUse::kOff:
      out.points = std::move(stereo_points_);
      out.frames = std::move(stereo_cues_);
      return out;
    case ContactUse::kAlways:
      out.points = std::move(stereo_points_);
      out.contacts_used = true;
      out.decision = "contacts with every frame's stereo (--contacts always)";
      break;
    case ContactUse::kWhereStereoFails: {
      const double agree = stereo_checked_ > 0 ? static_cast<double>(stereo_agreed_) / stereo_checked_ : NAN;
      std::size_t contacts = pending_.paired_floor.size() + pending_.ceiling_rays.size();
      for (const ClassPoint& p : contact_points_) contacts += p.source == PointSource::kContact;
      const bool stereo_fails =
          stereo_checked_ >= options_.stereo_check_min_pixels && agree < options_.stereo_check_min_agree;
      if (stereo_fails && contacts < static_cast<std::size_t>(options_.stereo_check_min_contacts)) {
        out.points = std::move(stereo_points_);
        out.decision = fmt::format(
            "walls placed by stereo, though it was consistent at "
            "only {:.0f} % of {} wall pixels: only {} "
            "floor/ceiling contacts to replace it (is the rig level, "
            "are wall bases in view?)",
            100 * agree, stereo_checked_, contacts);
      } else if (stereo_fails) {
        out.points = std::move(contact_points_);
        out.frames = std::move(contact_cues_);
        out.contacts_used = true;
        out.decision = fmt::format(
            "walls placed by their floor/ceiling contacts: their stereo was "
            "consistent at only {:.0f} % of {} wall "
            "pixels (plain walls; {:.0f} % needed to keep it)",
            100 * agree, stereo_checked_, 100 * options_.stereo_check_min_agree);
      } else {
        out.points = std::move(stereo_points_);
        out.decision = stereo_checked_ >= options_.stereo_check_min_pixels
                           ? fmt::format(
                                 "walls placed by stereo: it was consistent at "
                                 "{:.0f} % of {} wall pixels",
                                 100 * agree, stereo_checked_)
                           : fmt::format(
                                 "walls placed by stereo: only {} wall pixels could "
                                 "be checked",
                                 stereo_checked_);
      }
      break;
    }
  }
  if (out.frames.empty()) out.frames = std::move(stereo_cues_);
  if (out.contacts_used) {
    // Frames whose own feet did not show a board: all frames together may.
    const std::optional<double> board = pending_.MoveFeetBehindSkirting(options_.skirting_depth_m, &out.points);
    if (board) {
      for (FrameCues& c : out.frames) {
        if (std::isnan(c.skirting_height_m)) c.skirting_height_m = *board;
      }
    }
    out.contacts = pending_.Resolve(options_);
    out.points.insert(out.points.end(), out.contacts.points.begin(), out.contacts.points.end());
    out.contacts.points.clear();
  }
  return out;
}

}  // namespace asbuilt
