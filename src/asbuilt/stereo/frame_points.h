#ifndef ASBUILT_STEREO_FRAME_POINTS_H_
#define ASBUILT_STEREO_FRAME_POINTS_H_

// World points by class from stereo frames and their segmentation — the
// stereo stage's entry point for `asbuilt points` and `asbuilt survey`
// (PAPER.md §7). Per frame, three cues, each with evidence from both images:
//   corner  contour corners of each class region, matched along the row by
//           patch correlation (guided by the dense disparity), triangulated;
//   edge    image edges inside wall/door/window regions with horizontal
//           structure (wall–wall corners, frames, casings), matched the same
//           way — what carries textureless painted walls;
//   dense   every labelled pixel with a left–right consistent disparity;
//   contact where a wall (or door) label meets the floor below the horizon
//           or the ceiling above it: the pixel's ray cut with that plane.
//           The rig is level at a known height (capture.json), so the
//           floor is a plane at a known distance below the camera — a
//           "baseline" of ~1.5 m against the stereo pair's 0.12 m: a wall
//           4 m away is placed to ~1 cm per half pixel, where stereo gives
//           ~15 cm, and it needs no texture. Floor contacts are checked
//           against the floor's own disparity where it has any (furniture in
//           front of a wall base is not a contact); the ceiling's height is
//           estimated from columns that see both contacts of one wall.
//           A level camera sees a vertical wall at one depth down a column.
//           So the contact fixes the whole column (its wall pixels give no
//           stereo points), and the wall's stereo can be checked without
//           truth: it should agree down each column. By default
//           (ContactUse::kWhereStereoFails) the capture uses contacts only
//           where that check fails (plain paint), and stereo elsewhere.
// Points get σ from the disparity error: σ_Z = Z²·σ_d/(f·B). Nothing is
// interpolated where neither image has evidence.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/formats/capture.h"
#include "asbuilt/formats/points_file.h"
#include "asbuilt/geometry/rig.h"
#include "asbuilt/stereo/corners.h"
#include "asbuilt/stereo/disparity.h"
#include "asbuilt/stereo/frame_points_options.h"
#include "asbuilt/stereo/rectify.h"
#include "asbuilt/stereo/wall_vertices.h"
#include "asbuilt/util/progress.h"

namespace asbuilt {

// One rectified stereo frame with its labels, ready for ComputeFramePoints.
struct StereoFrame {
  cv::Mat left, right;          // Rectified CV_8UC3 (or CV_8UC1).
  cv::Mat labels_left;          // CV_8UC1 label ids, left view (required).
  cv::Mat labels_right;         // Optional; when given, matches must agree with it.
  PinholeCamera camera;         // Rectified intrinsics.
  double baseline_m = 0.12;
  RigPose pose;
  int index = -1;
};

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
  int boundary_points = 0;  // Door/window label edges on the wall.
  int vertex_points = 0;    // Wall–wall corner columns.
  int floor_contacts = 0;    // Wall/door–floor contact points.
  double skirting_height_m = NAN;  // A skirting's top seen over the wall feet (NAN: none).
  int floor_rejected = 0;    // Candidates whose floor disparity said "occluded".
  int ceiling_contacts = 0;  // Wall–ceiling contacts (rays until the height is known).
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

// A wall–ceiling contact waiting for the ceiling's height: the pixel's ray
// from the left camera, scaled so that its camera-frame z is 1.
struct ContactRay {
  LabelClass label = LabelClass::kWall;
  Vec3 origin_m = Vec3::Zero();
  Vec3 direction = Vec3::Zero();
  double fy_px = 0.0;  // For σ.
  int frame = -1;
};

// The ceiling's height above the floor.
struct CeilingHeight {
  double height_m = 0.0;
  double sigma_m = 0.0;
  int samples = 0;
};

struct ResolvedContacts {
  std::vector<ClassPoint> points;
  std::optional<CeilingHeight> ceiling;
  std::string how;            // "given", "from 812 of 950 columns …".
  int floor_rejected = 0;     // Floor contacts that disagreed with the ceiling (paired or topped).
  int ceiling_unused = 0;     // Ceiling contacts left unused (no height).
  int ceiling_rejected = 0;   // Ceiling contacts that a frame from the same spot saw wall above.
};

// Contacts that need the whole capture: the ceiling's height comes from all
// frames together. Collect each frame's with Append, then Resolve once.
struct PendingContacts {
  struct PairedFloor {
    ClassPoint point;            // The floor contact…
    double ceiling_sample_m;     // …and the ceiling height its column implies,
    double sample_sigma_m;       // with its σ from the rows.
  };
  // A floor contact whose column shows the wall (or its openings) all the
  // way up to the image's top edge: that wall is at least min_height_m tall.
  // Taller than the ceiling, it is no wall's base but the top of something
  // standing before a wall (a bed, a cabinet), projected far beyond it.
  struct ToppedFloor {
    ClassPoint point;
    double min_height_m;
    double sigma_m;
  };
  // What one frame shows at its top edge: per column, the lowest row down
  // to which the column is wall (or its openings) from the top (−1: its top
  // pixel is not). A topped floor contact is checked against every frame
  // taken from the same spot: near an image's side its own column's top
  // edge is low (rays there rise less for the same depth), and a bed's top
  // passes for a wall's base; the frame that sees it head-on shows the
  // "wall" reaching far above the ceiling.
  struct TopEdge {
    int frame = -1;  // Capture frame index (ClassPoint::frame).
    Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
    PinholeCamera camera;
    std::vector<int> wall_to_row;
  };
  std::vector<ContactRay> ceiling_rays;
  std::vector<PairedFloor> paired_floor;
  std::vector<ToppedFloor> topped_floor;
  std::vector<TopEdge> top_edges;
  // Rougher heights, from the wall's stereo depth just below each ceiling
  // contact: the fallback when too few columns see both of a wall's edges.
  std::vector<double> stereo_samples_m;

  void Append(PendingContacts&& other);
  // The ceiling's height (options.ceiling_height_m when given, else the
  // densest cluster of the paired samples, else of the stereo ones); the
  // paired floor contacts that agree with it, the topped ones it does not
  // rule out, and the ceiling contacts.
  ResolvedContacts Resolve(const FramePointsOptions& options) const;
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
    bool contacts_used = false;  // Contact points are among `points`.
    std::string decision;        // Why, in a sentence (empty with kOff).
    std::vector<FrameCues> frames;  // Each frame's cues, of the alternative chosen.
    int stereo_checked = 0, stereo_agreed = 0;
    ResolvedContacts contacts;   // Ceiling height and its provenance (points moved out).
  };
  Result Finish();

 private:
  FramePointsOptions options_;
  std::vector<ClassPoint> stereo_points_, contact_points_;
  std::vector<FrameCues> stereo_cues_, contact_cues_;
  PendingContacts pending_;
  int stereo_checked_ = 0, stereo_agreed_ = 0;
};

// The ceiling's height from samples: the median of their densest cluster
// (window max(2 cm, 1 %)), σ from its spread (MAD); nullopt with fewer than
// `min_samples`.
std::optional<CeilingHeight> CeilingHeightFromSamples(std::vector<double> samples_m, int min_samples = 20);
// Ceiling contact points from rays once the height is known (source kContact).
std::vector<ClassPoint> CeilingContactPoints(const std::vector<ContactRay>& rays, const CeilingHeight& ceiling,
                                             const FramePointsOptions& options);

// Points of one frame. Throws InvalidArgument on inconsistent sizes/types.
FramePointsResult ComputeFramePoints(const StereoFrame& frame, const FramePointsOptions& options);

// One level view of a single camera (a mono capture, or a view resampled
// from a panorama): no second image, so no disparity. Its optical centre is
// at pose.position_m (not offset by half a baseline), level (pitch 0).
struct MonoFrame {
  cv::Mat image;   // CV_8UC3 or CV_8UC1 (ceiling contacts snap to its edges).
  cv::Mat labels;  // CV_8UC1 label ids, the image's size.
  PinholeCamera camera;
  RigPose pose;
  int index = -1;
};

// Points of one mono frame: only what needs no stereo — floor and ceiling
// contacts (ContactUse::kAlways semantics, without the floor disparity
// check), and door/window boundary points at the contacts' depth. Gather
// them with a CapturePoints whose options say ContactUse::kAlways (the
// ceiling's height then comes from all frames). Corner, edge, dense and
// vertex points need a second view and are never produced. Throws
// InvalidArgument on inconsistent sizes/types.
FramePointsResult ComputeMonoFramePoints(const MonoFrame& frame, const FramePointsOptions& options);

// Labels for a frame's view: empty Mat when there are none (for the right
// view, "none" is normal). Images are as the capture's images (unrectified
// when the capture is); they are rectified with nearest-neighbour lookup.
using LabelProvider = std::function<cv::Mat(const CaptureFrame& frame, StereoEye eye)>;
// Left labels from DIR/NNN.png (frame index, three digits); right labels from
// DIR/right/NNN.png when present. Throws InputError if a left file is missing.
LabelProvider LabelsFromDirectory(const std::filesystem::path& dir);
// Left labels from each frame's `labels` key of capture.json.
LabelProvider LabelsFromCapture(const Capture& capture);

// Reads a frame's images and labels, rectifying them when the capture is not
// rectified (`rectifier` must then be given). Throws InputError for missing
// or unreadable images and labels, naming the file.
StereoFrame LoadStereoFrame(const Capture& capture, const CaptureFrame& frame,
                            const LabelProvider& labels, const StereoRectifier* rectifier);

struct CapturePointsResult {
  std::vector<ClassPoint> points;
  std::vector<FrameCues> frames;
  std::optional<CeilingHeight> ceiling;  // Estimated (or given) ceiling height.
  std::string wall_cue;                  // CapturePoints::Result::decision.
  double seconds = 0.0;

  // "12 frames, 45123 points (wall 40000, door 3000, window 2123; corner 150,
  // edge 3000, dense 41773, boundary 200, contact 900), 3.2 s".
  std::string BriefReport() const;
};

// Every frame of a capture (rectifying first when `rectified` is false,
// with the maps computed once from capture.calibration).
CapturePointsResult ComputeCapturePoints(const Capture& capture, const LabelProvider& labels,
                                         const FramePointsOptions& options,
                                         const ProgressCallback& progress = {});

// Coloured PLY (ASCII) for viewers: wall grey-blue, door brown, window cyan.
// Written atomically.
void WritePointsPly(const std::vector<ClassPoint>& points, const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_FRAME_POINTS_H_
