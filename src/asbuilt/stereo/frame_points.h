#ifndef ASBUILT_STEREO_FRAME_POINTS_H_
#define ASBUILT_STEREO_FRAME_POINTS_H_

// World points by class from one frame and its segmentation (PAPER.md §7):
// one pass that tags each point with the cue that placed it, each with
// evidence from both images where there are two:
//   corner  contour corners of each class region, matched along the row by
//           patch correlation (guided by the dense disparity), triangulated;
//   edge    image edges inside wall/door/window regions with horizontal
//           structure (wall–wall corners, frames, casings), matched the same
//           way — what carries textureless painted walls;
//   vertex  wall–wall corner columns, matched by their own profiles;
//   boundary door/window label edges on the wall, at the wall's depth;
//   dense   every labelled pixel with a left–right consistent disparity;
//   contact wall label edges with the floor or the ceiling (contacts.h).
// Points get σ from the disparity error: σ_Z = Z²·σ_d/(f·B). Nothing is
// interpolated where neither image has evidence. Which cue places the walls
// is the capture's choice (cue_choice.h); the loop over a capture's frames
// is capture_points.h.

#include <string>
#include <vector>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/stereo/contacts.h"
#include "asbuilt/stereo/corners.h"
#include "asbuilt/stereo/disparity.h"
#include "asbuilt/stereo/frame_points_options.h"
#include "asbuilt/stereo/stereo_frame.h"

namespace asbuilt {

// A corner with its stereo match, for reports and tests.
struct MatchedCorner {
  ClassCorner corner;
  RowMatch match;
  Vec3 point_in_world = Vec3::Zero();
};

// Which cues carried a frame (STYLE.md 6).
struct FrameCues {
  int index = -1;
  int corners_found = 0;
  int corners_matched = 0;
  int edge_candidates = 0;
  int edge_points = 0;
  int dense_points = 0;
  int dense_refined = 0;           // Of those, disparities set by the patch refinement (RefineDisparityAt).
  int boundary_points = 0;         // Door/window label edges on the wall.
  int vertex_points = 0;           // Wall–wall corner columns.
  int floor_contacts = 0;          // Wall/door–floor contact points.
  double skirting_height_m = NAN;  // A skirting's top seen over the wall feet (NAN: none).
  int floor_rejected = 0;          // Candidates whose floor disparity said "occluded".
  int ceiling_contacts = 0;        // Wall–ceiling contacts (rays until the height is known).
  // The stereo check (FramePointsOptions::contacts): wall pixels compared
  // with their column's median disparity, and how many agreed.
  int stereo_checked = 0;
  int stereo_agreed = 0;
  double dense_valid_fraction = NAN;  // Of labelled wall/door/window pixels.
  double seconds = 0.0;

  // "corner+edge+dense", or "none" — the cues that produced points.
  std::string CarriedBy() const;
  std::string BriefReport() const;
};

struct FramePointsResult {
  std::vector<ClassPoint> points;  // World frame.
  std::vector<MatchedCorner> corners;
  FrameCues cues;
  DisparityResult disparity;
  // Contacts that wait for the ceiling's height (PendingContacts).
  PendingContacts contacts;
  // ContactUse::kWhereStereoFails: `points` are the stereo alternative (as
  // with kOff); these the contact one (contacts, no wall stereo points,
  // boundaries at the contacts' depth). CapturePoints chooses.
  std::vector<ClassPoint> contact_points;
  FrameCues contact_cues;  // What the contact alternative's pass found.
};

// Points of one frame. Throws InvalidArgument on inconsistent sizes/types.
FramePointsResult ComputeFramePoints(const StereoFrame& frame, const FramePointsOptions& options);

// Points of one mono frame: only what needs no stereo — floor and ceiling
// contacts (ContactUse::kAlways semantics, without the floor disparity
// check), and door/window boundary points at the contacts' depth. Gather
// them with a CapturePoints whose options say ContactUse::kAlways (the
// ceiling's height then comes from all frames). Corner, edge, dense and
// vertex points need a second view and are never produced. Throws
// InvalidArgument on inconsistent sizes/types.
FramePointsResult ComputeMonoFramePoints(const MonoFrame& frame, const FramePointsOptions& options);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_FRAME_POINTS_H_
