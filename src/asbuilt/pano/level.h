#ifndef ASBUILT_PANO_LEVEL_H_
#define ASBUILT_PANO_LEVEL_H_

// A panorama's tilt, estimated from its own vertical edges, and the
// panorama resampled level (issue 42).
//
// Method. The world's vertical edges (room corners, door jambs, panel seams)
// all meet at the zenith, so the world's up is their common vanishing
// direction. The panorama is cut into turn-in-place perspective views (where
// straight edges stay straight), line segments are detected in each, and each
// segment's end points become rays r1, r2 in the pano frame: the plane through
// the centre and the segment has normal n = r1 × r2 / |r1 × r2|, and the up u
// of a vertical edge lies in that plane, n · u = 0. Segments whose plane comes
// within LevelOptions::max_tilt_deg of the frame's up count as vertical; u
// minimises Σ w (n · u)² with Cauchy weights by iteratively reweighted least
// squares (the smallest eigenvector of Σ w n nᵀ), starting from the frame's
// up. Any line in a vertical plane through the camera (a floor seam that runs
// away from it) constrains u in the same way and counts as vertical. Then,
// with use_horizontal_lines, the room's two horizontal Manhattan directions
// h1, h2 join in (their yaw searched around u): the frame (h1, h2, u) is
// turned to minimise the same robust sum over all segments, each against the
// axis it fits best (n · h = 0 for a line along h), by reweighted
// Gauss–Newton. Each segment's residual is scaled by its expected error: the
// sine of its angle to the axis over its length. Each direction is cut into
// two views whose crops differ, so detection noise averages.
//
//   PanoTilt tilt = EstimatePanoTilt(equirect_bgr);
//   if (tilt.Found()) equirect_bgr = LevelPanorama(equirect_bgr, tilt);
//
// Frames: the pano frame of pano/perspective.h (+Z up, yaw 0 along +Y, yaw
// counter-clockwise seen from above; equirect column u looks along yaw
// −360°·(u + 0.5)/W).

#include <string>
#include <vector>

#include "asbuilt/geometry/rig.h"
#include "asbuilt/imageio/image.h"
#include "asbuilt/pano/perspective.h"

namespace asbuilt {

struct LevelOptions {
  double max_tilt_deg = 10.0;  // Largest tilt searched; a segment whose plane misses up by more is not vertical.
  int views = 8;               // Views per turn (two turns, offset by half a step), evenly turned.
  double view_vertical_fov_deg = 120;  // Each view's vertical field of view (< 180); taller sees more of each edge.
  double min_segment_deg = 3.0;        // Shortest segment used, as an angle seen from the centre.
  bool use_horizontal_lines = true;    // Also fit the room's horizontal Manhattan lines (off: vertical lines only).
  int min_lines = 12;                  // Fewer vertical segments than this: no estimate (PanoTilt::found false).
  int bootstrap_samples = 100;         // Resamples of the segments for sigma_deg (cost grows with it); 0 = sigma NaN.
  unsigned seed = 42;                  // Seed of the bootstrap.
  void Check() const;                  // Throws InvalidArgument naming a bad field.
};

// The panorama's tilt: where the world's up points in the pano frame.
struct PanoTilt {
  Vec3 up_in_pano = Vec3::UnitZ();  // Unit; the world's up in the pano frame (+Z when level).
  double tilt_deg = 0.0;            // Angle between up_in_pano and the frame's +Z.
  // Yaw (pano frame, [0, 360)) of the horizontal part of up_in_pano: the
  // world's up leans that way, so the true horizon lies below the middle row
  // there and above it opposite. 0 when the tilt is 0.
  double toward_yaw_deg = 0.0;
  int lines_used = 0;      // Segments the estimate rests on (inliers: Cauchy weight > 1/2), all axes.
  int vertical_lines = 0;  // Of which vertical (when not found: the vertical segments seen).
  // 1σ of up_in_pano, degrees: the larger axis of the bootstrap scatter, the
  // segments resampled in clusters of nearby ones. Errors that many segments
  // share (stitching, lens, a room not square) are not in it. NaN when not
  // found or not computed.
  double sigma_deg = 0.0;
  // False when fewer than LevelOptions::min_lines vertical segments were seen
  // (or fitted), or the fit leaned more than max_tilt_deg: up_in_pano is then
  // +Z, tilt 0.
  bool found = false;

  // Column of the equirectangular image (width_px wide) that looks toward toward_yaw_deg.
  double TowardColumn(int width_px) const;
  // "tilted 0.80° toward yaw 328° (column 92 of 1024) ± 0.03°, 412 lines (130 vertical)",
  // or "no tilt estimate: 5 vertical lines, too few". The column is left out when width_px is 0.
  std::string BriefReport(int width_px = 0) const;
};

// Estimates the tilt of an equirectangular panorama (8-bit, 1 or 3 channels,
// BGR, twice as wide as high ±1 px). When fewer than options.min_lines
// vertical segments are found, returns found = false, up +Z, tilt 0,
// sigma NaN and vertical_lines the count seen: it does not guess. Throws
// InvalidArgument for an empty image, one not 2:1, or one of another type,
// and for bad options.
PanoTilt EstimatePanoTilt(const Image& equirect, const LevelOptions& options = {});

// The panorama resampled so that tilt.up_in_pano becomes the frame's up, by
// the smallest rotation that does it (about the horizontal axis
// up_in_pano × Z: no turn about the vertical, column 0 keeps looking the same
// way). Bilinear, wrapping across the 0/360° seam; same size, channels and
// type as `equirect` (any of imageio's types). A tilt that was not found (or
// is 0) gives an unchanged copy. Throws InvalidArgument for an empty image,
// one not 2:1 or a non-unit up_in_pano.
Image LevelPanorama(const Image& equirect, const PanoTilt& tilt);

// The tilt of a rig of perspective views taken from one spot (a mono
// capture: one camera turning in place, its views said to be level), from
// the same lines in all of them: each view's segments are turned into the
// rig's frame by its geometry (yaw, camera), and the world's up is found
// there as for a panorama (a tripod whose axis leans tilts every view
// alike). Views must be 8-bit grey or BGR, one geometry each, of its
// camera's size; throws InvalidArgument otherwise. found is false, as for a
// panorama, with too few vertical lines.
PanoTilt EstimateViewsTilt(const std::vector<Image>& views, const std::vector<PanoView>& geometry,
                           const LevelOptions& options = {});

// One view of such a rig resampled as the level view of the same yaw and
// camera would see it (bilinear; pixels that fall outside take the nearest
// edge's). A tilt not found gives an unchanged copy.
Image LevelView(const Image& view, const PanoView& geometry, const PanoTilt& tilt);

// The rotation LevelPanorama applies: level_from_pano · up_in_pano = +Z.
Mat3 LevelFromPano(const Vec3& up_in_pano);

}  // namespace asbuilt

#endif  // ASBUILT_PANO_LEVEL_H_
