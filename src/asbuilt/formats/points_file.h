#ifndef ASBUILT_FORMATS_POINTS_FILE_H_
#define ASBUILT_FORMATS_POINTS_FILE_H_

// The labelled point file (PAPER.md §7: "store corner points by class in a
// labelled text file"): the output of `asbuilt points` and the input of
// `asbuilt plan`. One point per line, world metres:
//
//   # asbuilt points v1
//   # class x y z sigma_m source frame
//   wall 1.2345 5.6789 1.5000 0.0040 corner 3
//   door 2.0000 0.0000 2.1000 0.0100 dense 4
//
// `class` is wall, door or window (or the label id 1/2/3); `sigma_m` is the
// point's 1σ position uncertainty (from the disparity error); `source` is
// corner (matched contour corner), dense (per-pixel disparity), edge
// (structure line: wall–floor, wall–ceiling, wall–wall), boundary, contact,
// vertex (a wall–wall corner column) or other; `frame`
// the capture frame index, −1 if none. The last three columns are optional
// when reading (the paper's `class x y z` files load with sigma 0, source
// other, frame −1). Lines starting with '#' and blank lines are skipped.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "asbuilt/geometry/rig.h"
#include "asbuilt/geometry/label_class.h"

namespace asbuilt {

// kBoundary: a door/window label edge (wall on the other side) placed on the
// wall's surface — it fixes an opening's width, not the wall's position.
// kContact: where a wall (or door) label meets the floor or the ceiling,
// placed on that plane along the pixel's ray — the level rig's height is the
// baseline, ten times the stereo one, so these fix a wall's position even
// where the wall has no texture for stereo.
// kVertex: a vertical wall–wall corner (a room vertex), found as a column
// where two walls' shading meets on every row and matched in the right view
// by its intensity profile — it carries near plain walls whose floor and
// ceiling edges are out of view.
enum class PointSource : std::uint8_t { kCorner, kDense, kEdge, kOther, kBoundary, kContact, kVertex };
const char* PointSourceName(PointSource s);

// A floor contact whose image column also saw the wall's ceiling edge, and
// the ceiling height that column implies: stereo/contacts.h measures them,
// plan/verdict.h reads a tilted photo from how they vary round the room.
struct CeilingSample {
  Vec3 floor_m = Vec3::Zero();  // The floor contact, world m.
  int frame = -1;
  double height_m = 0.0;
};

struct ClassPoint {
  LabelClass label = LabelClass::kWall;
  Vec3 position_m = Vec3::Zero();  // World frame.
  double sigma_m = 0.0;
  PointSource source = PointSource::kOther;
  int frame = -1;
};

// Reads a point file. Throws InputError naming the file and the line
// ("points.txt: line 12: expected 4 to 7 columns, got 2").
std::vector<ClassPoint> ReadPoints(const std::filesystem::path& path);
// Same, from text in memory; `name` stands for the file in messages.
std::vector<ClassPoint> ParsePoints(std::string_view text, const std::string& name);
// Writes atomically, with the header comment.
void WritePoints(const std::vector<ClassPoint>& points, const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_FORMATS_POINTS_FILE_H_
