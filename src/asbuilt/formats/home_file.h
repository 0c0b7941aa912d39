#ifndef ASBUILT_FORMATS_HOME_FILE_H_
#define ASBUILT_FORMATS_HOME_FILE_H_

// home.json — a whole home as a list of rooms, each its own capture
// (docs/formats.md "home.json"):
//
//   {"version": 1, "kind": "home",
//    "rooms": [{"name": "kitchen", "capture": "kitchen/capture.json",
//               "hint": {"position_m": [4.0, 0.5], "yaw_deg": 90},
//               "labels": "kitchen/labels"}, ...]}
//
// `capture` and `labels` are relative to home.json's folder. Names are unique
// and usable as folder names (each room's outputs go to OUT/rooms/NAME/). A
// capture file that is missing is not an error of the home file: the survey
// reports that room and goes on with the others.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "asbuilt/formats/capture.h"
#include "asbuilt/geometry/rig.h"

namespace asbuilt {

// Where the user knows a room roughly is: its capture frame's origin in the
// home frame and how far its axes are turned, counter-clockwise.
struct HomeRoomHint {
  Vec2 position_m = Vec2::Zero();
  double yaw_deg = 0.0;
};

struct HomeRoom {
  std::string name;
  std::filesystem::path capture;  // Resolved against home.json's folder.
  std::optional<HomeRoomHint> hint;
  std::optional<std::filesystem::path> labels;  // What `survey --labels` takes, for this room.
};

struct Home {
  int version = 1;
  std::filesystem::path file;  // home.json as given.
  std::vector<HomeRoom> rooms;
};

// Reads and validates home.json. Throws InputError listing every problem
// with its field path (`home.json: rooms[2].name: "kitchen" is also
// rooms[0]'s name`).
Home ReadHome(const std::filesystem::path& path);
FileReport CheckHomeFile(const std::filesystem::path& path);

// Whether `path` is a JSON file whose "kind" is "home" (false for anything
// unreadable: the caller's own reader then names the problem).
bool IsHomeFile(const std::filesystem::path& path);

}  // namespace asbuilt

#endif  // ASBUILT_FORMATS_HOME_FILE_H_
