#ifndef ASBUILT_STEREO_CONTACTS_H_
#define ASBUILT_STEREO_CONTACTS_H_

// The contact cue: where a wall (or door) label meets the floor below the
// horizon or the ceiling above it, the pixel's ray cut with that plane. The
// rig is level at a known height (capture.json), so the floor is a plane at
// a known distance below the camera — a "baseline" of ~1.5 m against the
// stereo pair's 0.12 m: a wall 4 m away is placed to ~1 cm per half pixel,
// where stereo gives ~15 cm, and it needs no texture. Floor contacts are
// checked against the floor's own disparity where it has any (furniture in
// front of a wall base is not a contact); the ceiling's height is estimated
// from the columns that see both contacts of one wall, over all frames
// (PendingContacts::Resolve). A level camera sees a vertical wall at one
// depth down a column, so the contact fixes the whole column (its wall
// pixels give no stereo points), and the wall's stereo can be checked
// without truth (cue_choice.h). docs/stereo.md, "How a frame becomes points" 6.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "asbuilt/formats/points_file.h"
#include "asbuilt/geometry/rig.h"
#include "asbuilt/stereo/frame_points_options.h"
#include "asbuilt/stereo/stereo_frame.h"

namespace asbuilt {

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
  std::string how;                  // "given", "from 812 of 950 columns …".
  int floor_rejected = 0;           // Floor contacts that disagreed with the ceiling (paired or topped).
  int ceiling_unused = 0;           // Ceiling contacts left unused (no height).
  int ceiling_rejected = 0;         // Ceiling contacts that a frame from the same spot saw wall above.
  int ceiling_boundary_points = 0;  // Opening edges placed at the depth of the ceiling contacts beside them.
  // Every floor contact whose column also saw the wall's ceiling edge.
  std::vector<CeilingSample> ceiling_samples;
};

// One frame's wall feet pooled by height above the floor (the skirting
// profile of contacts.cc): the signed brightness steps above each foot in
// 5 mm bins from 3 cm up. Kept so the frames of one capture decide together
// where no frame alone saw a board (PendingContacts::MoveFeetBehindSkirting).
struct SkirtingEvidence {
  static constexpr int kBins = 44;  // 3–25 cm.
  std::array<double, kBins> sum{}, sum_sq{};
  std::array<int, kBins> count{};
  int feet = 0;
  int frame = -1;
  bool moved = false;  // The frame's own feet told, and were moved behind the board.
  Eigen::Isometry3d world_from_cam = Eigen::Isometry3d::Identity();
  PinholeCamera camera;
};

// Contacts that need the whole capture: the ceiling's height comes from all
// frames together. Collect each frame's with Append, then Resolve once.
struct PendingContacts {
  struct PairedFloor {
    ClassPoint point;         // The floor contact…
    double ceiling_sample_m;  // …and the ceiling height its column implies,
    double sample_sigma_m;    // with its σ from the rows.
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
  // A door or window's side edge where no floor contact gives the wall's
  // depth beside it (a near door: its foot lies below the view): the wall's
  // ceiling edge beside it gives that depth once the ceiling's height is
  // known. A level camera sees the wall at one depth down each column.
  // So does the head of an opening below a ceiling contact in a column with
  // no floor contact: one of the opening's own points (kContact), where a
  // side edge is a label edge (kBoundary).
  struct CeilingBoundary {
    ContactRay edge;   // The label edge's pixel (its label the opening's).
    double wall_rise;  // World rise per unit camera depth of the ceiling contacts beside it.
    PointSource source = PointSource::kBoundary;
  };
  std::vector<ContactRay> ceiling_rays;
  std::vector<CeilingBoundary> ceiling_boundaries;
  std::vector<PairedFloor> paired_floor;
  std::vector<ToppedFloor> topped_floor;
  std::vector<TopEdge> top_edges;
  // Rougher heights, from the wall's stereo depth just below each ceiling
  // contact: the fallback when too few columns see both of a wall's edges.
  std::vector<double> stereo_samples_m;
  std::vector<SkirtingEvidence> skirting;  // One per frame with wall feet.

  void Append(PendingContacts&& other);
  // A skirting's top is one height all round a room: where no frame's own
  // feet told, the feet of all frames together may. When they do, the wall
  // floor contacts of every frame that did not move its own (in `points`,
  // and the paired and topped ones here) move `depth_m` back, as a frame
  // moves them (before Resolve: the paired samples follow). Returns the
  // board's height, or nullopt (nothing moved).
  std::optional<double> MoveFeetBehindSkirting(double depth_m, std::vector<ClassPoint>* points);
  // The ceiling's height (options.ceiling_height_m when given, else the
  // densest cluster of the paired samples, else of the stereo ones); the
  // paired floor contacts that agree with it, the topped ones it does not
  // rule out, the ceiling contacts, and the opening edges placed by them.
  ResolvedContacts Resolve(const FramePointsOptions& options) const;
};

// One frame's contacts: per column (every contact_col_step_px), the lowest
// clean wall/door → floor label edge below the horizon (unless the floor's
// disparity below it says something nearer stands there) and the highest
// clean ceiling → wall edge above it.
struct FrameContacts {
  // Floor contacts placed now (world frame, source kContact, z = 0).
  std::vector<ClassPoint> points;
  // Floor contacts paired with a ceiling edge or topped by the image's edge,
  // ceiling rays, this frame's top edge: they wait for the ceiling's height.
  PendingContacts pending;
  // CV_8U of the labels' size: 1 on each contacted column's wall run. A
  // level camera sees a vertical wall at one depth down a column, so the
  // contact already places those pixels; their stereo points add only noise.
  cv::Mat covered;
  // Per image column: the wall's disparity (px) at its floor contact's
  // depth, f·B/z (NaN: no floor contact there).
  std::vector<float> wall_disparity_px;
  // Per image column: the world rise per unit camera depth of its ceiling
  // contact's ray (NaN: none), for CeilingBoundary.
  std::vector<float> ceiling_rise;
  int floor_contacts = 0;
  int floor_rejected = 0;  // Candidates whose floor disparity said "occluded".
  int ceiling_contacts = 0;
  double skirting_height_m = NAN;  // A skirting's top seen over the wall feet (NaN: none).
};

// The contacts of a rectified frame (labels_left required) with its
// disparity map `disparity_px` (CV_32F of the labels' size, NaN where
// invalid; all NaN for a mono view: no floor check). Nothing when the left
// camera is not above the floor (height ≤ 5 cm).
FrameContacts FindFrameContacts(const StereoFrame& frame, const cv::Mat& disparity_px,
                                const FramePointsOptions& options);

// The ceiling's height from samples: the median of their densest cluster
// (window max(2 cm, 1 %)), σ from its spread (MAD); nullopt with fewer than
// `min_samples`.
std::optional<CeilingHeight> CeilingHeightFromSamples(std::vector<double> samples_m, int min_samples = 20);
// Ceiling contact points from rays once the height is known (source kContact).
std::vector<ClassPoint> CeilingContactPoints(const std::vector<ContactRay>& rays, const CeilingHeight& ceiling,
                                             const FramePointsOptions& options);

}  // namespace asbuilt

#endif  // ASBUILT_STEREO_CONTACTS_H_
